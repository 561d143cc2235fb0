#pragma once
#include <cstdint>

namespace stillslam {

// How word weights are computed (DBoW2 names). tf = occurrences of the word in
// the image / features in the image; idf = ln(N / N_w) over the N training
// images, N_w of which contain the word.
enum class WordWeighting : std::uint32_t { kTfIdf = 0, kTf = 1, kIdf = 2, kBinary = 3 };

const char* to_string(WordWeighting w);

struct VocabularyOptions {
  int branching = 10;  // k: children per node (ORB-SLAM: 10)
  int levels = 5;      // L: tree depth below the root (ORB-SLAM: 6); at most k^L words
  WordWeighting weighting = WordWeighting::kTfIdf;
  std::uint64_t seed = 0;       // k-means++ seeding; same seed and data give the same tree
  int max_iterations = 10;      // k-majority iterations per node (stops early on convergence)
};

}  // namespace stillslam
