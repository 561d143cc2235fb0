#pragma once
// k-means for binary descriptors: k-means++ seeding on Hamming distance and
// per-bit majority centres (Grana et al., "k-majority"). One node of the
// vocabulary tree is one call.
#include <cstdint>
#include <random>
#include <vector>

#include "stillslam/place/binary_descriptor.h"

namespace stillslam::place_detail {

struct BinaryCluster {
  Descriptor256 centre{};
  std::vector<std::uint32_t> members;  // indices into the data, ascending
};

// Splits data[members] into at most k non-empty clusters; fewer when there are
// fewer distinct descriptors. Every member ends up in the cluster with the
// nearest centre (ties to the lower cluster index), exactly the rule
// Vocabulary::word_of uses when descending the tree.
std::vector<BinaryCluster> cluster_k_majority(const std::vector<Descriptor256>& data,
                                              const std::vector<std::uint32_t>& members, int k,
                                              int max_iterations, std::mt19937_64& rng);

}  // namespace stillslam::place_detail
