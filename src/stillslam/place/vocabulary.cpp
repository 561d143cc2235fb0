#include "stillslam/place/vocabulary.h"

#include <algorithm>
#include <limits>

#include "stillslam/core/check.h"

namespace stillslam {

using place_detail::Descriptor256;
using place_detail::hamming;

const char* to_string(WordWeighting w) {
  switch (w) {
    case WordWeighting::kTfIdf: return "tf-idf";
    case WordWeighting::kTf: return "tf";
    case WordWeighting::kIdf: return "idf";
    case WordWeighting::kBinary: return "binary";
  }
  return "unknown";
}

void Vocabulary::index_tree() {
  const std::size_t n = descriptors_.size();
  parent_.assign(n, 0);
  depth_.assign(n, 0);
  for (NodeId p = 0; p < n; ++p)
    for (std::uint32_t c = 0; c < child_count_[p]; ++c) {
      parent_[first_child_[p] + c] = p;
      depth_[first_child_[p] + c] = static_cast<std::uint8_t>(depth_[p] + 1);
    }
  node_word_.assign(n, kNoWord);
  for (WordId w = 0; w < word_node_.size(); ++w) node_word_[word_node_[w]] = w;
}

WordId Vocabulary::word_of(const std::uint8_t* descriptor, NodeId* node_at_level, int level) const {
  STILLSLAM_CHECK(!empty(), "Vocabulary::word_of: the vocabulary is empty (train or load one first)");
  const Descriptor256 d = place_detail::pack(descriptor);
  NodeId node = 0;
  NodeId at_level = 0;
  while (child_count_[node] > 0) {
    const NodeId first = first_child_[node];
    const NodeId last = first + child_count_[node];
    NodeId best = first;
    int best_distance = std::numeric_limits<int>::max();
    for (NodeId c = first; c < last; ++c) {
      const int dist = hamming(d, descriptors_[c]);
      if (dist < best_distance) {
        best_distance = dist;
        best = c;
      }
    }
    node = best;
    if (depth_[node] == level) at_level = node;
  }
  // A word shallower than the requested level is its own group.
  if (node_at_level) *node_at_level = (level > 0 && depth_[node] < level) ? node : at_level;
  return node_word_[node];
}

void Vocabulary::transform(const cv::Mat& descriptors, BowVector& bow, FeatureVector& features,
                           int direct_index_level) const {
  bow.entries.clear();
  features.groups.clear();
  if (descriptors.empty()) return;
  STILLSLAM_CHECK_EQ(descriptors.type(), CV_8UC1, "Vocabulary::transform: pass N x 32 CV_8U ORB descriptors");
  STILLSLAM_CHECK_EQ(descriptors.cols, 32, "Vocabulary::transform: pass N x 32 CV_8U ORB descriptors");
  const bool direct = direct_index_level > 0;
  std::vector<std::pair<WordId, double>> words;
  words.reserve(static_cast<std::size_t>(descriptors.rows));
  std::vector<std::pair<NodeId, std::uint32_t>> nodes;
  if (direct) nodes.reserve(static_cast<std::size_t>(descriptors.rows));
  for (int r = 0; r < descriptors.rows; ++r) {
    NodeId node = 0;
    const WordId w = word_of(descriptors.ptr<std::uint8_t>(r), &node, direct_index_level);
    words.emplace_back(w, word_weight_[w]);
    if (direct) nodes.emplace_back(node, static_cast<std::uint32_t>(r));
  }
  std::sort(words.begin(), words.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  // tf-idf and tf add one weight per occurrence; idf and binary count a word once.
  const bool per_occurrence = weighting_ == WordWeighting::kTfIdf || weighting_ == WordWeighting::kTf;
  for (const auto& [w, weight] : words) {
    if (!bow.entries.empty() && bow.entries.back().first == w) {
      if (per_occurrence) bow.entries.back().second += weight;
    } else {
      bow.entries.emplace_back(w, weight);
    }
  }
  // Words seen in every training image carry no information (idf 0).
  std::erase_if(bow.entries, [](const auto& e) { return e.second <= 0; });
  bow.normalize_l1();
  if (direct) {
    std::sort(nodes.begin(), nodes.end());
    for (const auto& [node, row] : nodes) {
      if (features.groups.empty() || features.groups.back().node != node) features.groups.push_back({node, {}});
      features.groups.back().features.push_back(row);
    }
  }
}

BowVector Vocabulary::transform(const cv::Mat& descriptors) const {
  BowVector bow;
  FeatureVector unused;
  transform(descriptors, bow, unused, 0);
  return bow;
}

bool Vocabulary::operator==(const Vocabulary& o) const {
  return branching_ == o.branching_ && levels_ == o.levels_ && weighting_ == o.weighting_ &&
         training_images_ == o.training_images_ && training_descriptors_ == o.training_descriptors_ &&
         descriptors_ == o.descriptors_ && first_child_ == o.first_child_ && child_count_ == o.child_count_ &&
         word_node_ == o.word_node_ && word_weight_ == o.word_weight_;
}

}  // namespace stillslam
