#pragma once
// Bag-of-words image descriptions produced by Vocabulary::transform.
#include <cstdint>
#include <utility>
#include <vector>

namespace stillslam {

using WordId = std::uint32_t;  // leaf of the vocabulary tree, 0..Vocabulary::size()-1
using NodeId = std::uint32_t;  // any node of the tree; 0 is the root

// Sparse weighted word histogram, sorted by word id, one entry per word.
// Vectors from Vocabulary::transform are L1-normalized (weights sum to 1).
struct BowVector {
  std::vector<std::pair<WordId, double>> entries;

  std::size_t size() const { return entries.size(); }
  bool empty() const { return entries.empty(); }
  auto begin() const { return entries.begin(); }
  auto end() const { return entries.end(); }
  // Weight of `word`, 0 when absent (binary search).
  double weight(WordId word) const;
  // Sum of |weight| (1 for normalized vectors, 0 for empty ones).
  double l1_norm() const;
  // Divides every weight by the L1 norm; no-op for empty or all-zero vectors.
  void normalize_l1();
};

// Builds a BowVector from unsorted (word, weight) pairs, summing duplicates.
BowVector make_bow_vector(std::vector<std::pair<WordId, double>> pairs);

// L1 similarity in [0, 1]: 1 - 0.5 * | a/|a| - b/|b| |_1 (Nister & Stewenius,
// as in DBoW2). 1 for identical histograms, 0 for disjoint or empty ones.
double l1_score(const BowVector& a, const BowVector& b);

// The direct index: an image's feature indices grouped by the vocabulary node
// their descriptors pass through at a chosen tree depth, sorted by node id.
// Features in different groups are unlikely to match, so matching only within
// shared groups is a cheap pre-filter (see match_by_direct_index).
struct FeatureGroup {
  NodeId node = 0;
  std::vector<std::uint32_t> features;  // rows of the image's descriptor matrix, ascending
};

struct FeatureVector {
  std::vector<FeatureGroup> groups;

  std::size_t size() const { return groups.size(); }
  bool empty() const { return groups.empty(); }
  auto begin() const { return groups.begin(); }
  auto end() const { return groups.end(); }
  // The features under `node`, or nullptr (binary search).
  const std::vector<std::uint32_t>* features_of(NodeId node) const;
};

}  // namespace stillslam
