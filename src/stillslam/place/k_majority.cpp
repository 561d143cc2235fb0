#include "stillslam/place/k_majority.h"

#include <algorithm>
#include <limits>

namespace stillslam::place_detail {
namespace {

// k-means++: each further centre is drawn with probability proportional to
// its squared distance to the nearest centre so far. Uses rng() % total
// (not std::uniform_int_distribution) so the tree is identical across
// standard libraries.
std::vector<Descriptor256> seed_centres(const std::vector<Descriptor256>& data,
                                        const std::vector<std::uint32_t>& members, int k,
                                        std::mt19937_64& rng) {
  const std::size_t n = members.size();
  std::vector<Descriptor256> centres;
  centres.push_back(data[members[rng() % n]]);
  std::vector<int> nearest(n, std::numeric_limits<int>::max());
  while (static_cast<int>(centres.size()) < k) {
    std::uint64_t total = 0;
    for (std::size_t i = 0; i < n; ++i) {
      nearest[i] = std::min(nearest[i], hamming(data[members[i]], centres.back()));
      total += static_cast<std::uint64_t>(nearest[i]) * static_cast<std::uint64_t>(nearest[i]);
    }
    if (total == 0) break;  // every member equals some centre already
    std::uint64_t r = rng() % total;
    std::size_t pick = 0;
    for (; pick < n; ++pick) {
      const auto d2 = static_cast<std::uint64_t>(nearest[pick]) * static_cast<std::uint64_t>(nearest[pick]);
      if (r < d2) break;
      r -= d2;
    }
    centres.push_back(data[members[pick]]);
  }
  return centres;
}

// Nearest centre per member; returns true when any assignment changed.
bool assign(const std::vector<Descriptor256>& data, const std::vector<std::uint32_t>& members,
            const std::vector<Descriptor256>& centres, std::vector<int>& assignment) {
  bool changed = false;
  for (std::size_t i = 0; i < members.size(); ++i) {
    const Descriptor256& d = data[members[i]];
    int best = 0, best_distance = std::numeric_limits<int>::max();
    for (std::size_t c = 0; c < centres.size(); ++c) {
      const int dist = hamming(d, centres[c]);
      if (dist < best_distance) {
        best_distance = dist;
        best = static_cast<int>(c);
      }
    }
    if (assignment[i] != best) {
      assignment[i] = best;
      changed = true;
    }
  }
  return changed;
}

}  // namespace

std::vector<BinaryCluster> cluster_k_majority(const std::vector<Descriptor256>& data,
                                              const std::vector<std::uint32_t>& members, int k,
                                              int max_iterations, std::mt19937_64& rng) {
  if (members.empty() || k < 1) return {};
  std::vector<Descriptor256> centres = seed_centres(data, members, k, rng);
  std::vector<int> assignment(members.size(), -1);
  assign(data, members, centres, assignment);
  for (int it = 0; it < max_iterations; ++it) {
    std::vector<BitMajority> votes(centres.size());
    for (std::size_t i = 0; i < members.size(); ++i) votes[assignment[i]].add(data[members[i]]);
    // An emptied cluster keeps its centre; it is dropped below if it stays empty.
    for (std::size_t c = 0; c < centres.size(); ++c)
      if (votes[c].size() > 0) centres[c] = votes[c].centre();
    if (!assign(data, members, centres, assignment)) break;
  }
  std::vector<BinaryCluster> clusters(centres.size());
  for (std::size_t c = 0; c < centres.size(); ++c) clusters[c].centre = centres[c];
  for (std::size_t i = 0; i < members.size(); ++i) clusters[assignment[i]].members.push_back(members[i]);
  // Dropping an empty cluster keeps the nearest-centre property: nobody was
  // nearest to it.
  std::erase_if(clusters, [](const BinaryCluster& c) { return c.members.empty(); });
  return clusters;
}

}  // namespace stillslam::place_detail
