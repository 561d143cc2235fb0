#pragma once
// Hierarchical k-majority vocabulary tree over 256-bit ORB descriptors
// (Nister & Stewenius 2006; Galvez-Lopez & Tardos 2012, "DBoW2"), written for
// stillslam: training, transform to TF-IDF bag-of-words vectors plus a direct
// index, L1 scoring, and a compact binary file format.
//
// The tree is stored flat in breadth-first order, so the children of a node
// are a contiguous id range; leaves are the words. Immutable after training
// or loading: transform/score are const and thread-safe.
#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>
#include <vector>

#include "stillslam/place/binary_descriptor.h"
#include "stillslam/place/bow_vector.h"
#include "stillslam/place/vocabulary_options.h"

namespace stillslam {

class Vocabulary {
 public:
  Vocabulary() = default;

  // Hierarchical k-means (k-means++ seeding, per-bit majority centres) on all
  // descriptors of all images; idf weights from the same images. Each element
  // is one image's N x 32 CV_8U descriptor matrix (empty ones are skipped).
  // Deterministic for a given seed. Throws stillslam::Error on bad options or
  // when there are no descriptors at all.
  static Vocabulary train(const std::vector<cv::Mat>& descriptors_per_image, const VocabularyOptions& options);

  // Words of an image. `direct_index_level` is the tree depth (1 = the root's
  // children, levels() = leaves) whose nodes group the features in
  // `features`; a word shallower than that level is its own group. 0 or a
  // negative level leaves `features` empty. ORB-SLAM's choice (4 levels up
  // from the leaves of a 6-level tree) is depth 2.
  void transform(const cv::Mat& descriptors, BowVector& bow, FeatureVector& features,
                 int direct_index_level) const;
  BowVector transform(const cv::Mat& descriptors) const;
  // The word of one descriptor (32 bytes) and, optionally, its ancestor at
  // `level` (see transform).
  WordId word_of(const std::uint8_t* descriptor, NodeId* node_at_level = nullptr, int level = 0) const;

  double score(const BowVector& a, const BowVector& b) const { return l1_score(a, b); }

  // Compact little-endian binary file (format in vocabulary_io.cpp). Throws
  // stillslam::Error naming the file when it cannot be written or read, or is
  // not a stillslam vocabulary (e.g. a DBoW2 ORBvoc.txt).
  void save(const std::filesystem::path& path) const;
  static Vocabulary load(const std::filesystem::path& path);

  std::size_t size() const { return word_node_.size(); }  // number of words
  std::size_t node_count() const { return descriptors_.size(); }
  int k() const { return branching_; }
  int depth() const { return levels_; }
  bool empty() const { return word_node_.empty(); }
  WordWeighting weighting() const { return weighting_; }
  double word_weight(WordId w) const { return word_weight_.at(w); }
  NodeId word_node(WordId w) const { return word_node_.at(w); }
  // Depth of a node (root 0).
  int node_depth(NodeId n) const { return depth_.at(n); }
  std::uint64_t training_images() const { return training_images_; }
  std::uint64_t training_descriptors() const { return training_descriptors_; }

  // Field-by-field equality (used by round-trip tests).
  bool operator==(const Vocabulary& other) const;

 private:
  friend class VocabularyBuilder;
  friend class VocabularyReader;
  static constexpr WordId kNoWord = 0xFFFFFFFFu;

  // Fills depth_, parent_ and node_word_ from the tree and word_node_.
  void index_tree();

  int branching_ = 0;
  int levels_ = 0;
  WordWeighting weighting_ = WordWeighting::kTfIdf;
  std::uint64_t training_images_ = 0;
  std::uint64_t training_descriptors_ = 0;
  // Per node (breadth-first order; the root's descriptor is unused).
  std::vector<place_detail::Descriptor256> descriptors_;
  std::vector<NodeId> first_child_;
  std::vector<std::uint32_t> child_count_;  // 0 for leaves
  // Per word.
  std::vector<NodeId> word_node_;
  std::vector<double> word_weight_;
  // Derived by index_tree().
  std::vector<WordId> node_word_;
  std::vector<NodeId> parent_;
  std::vector<std::uint8_t> depth_;
};

}  // namespace stillslam
