#include "stillslam/place/bow_vector.h"

#include <algorithm>
#include <cmath>

namespace stillslam {

double BowVector::weight(WordId word) const {
  const auto it = std::lower_bound(entries.begin(), entries.end(), word,
                                   [](const auto& e, WordId w) { return e.first < w; });
  return it != entries.end() && it->first == word ? it->second : 0.0;
}

double BowVector::l1_norm() const {
  double n = 0;
  for (const auto& [w, v] : entries) n += std::abs(v);
  return n;
}

void BowVector::normalize_l1() {
  const double n = l1_norm();
  if (n <= 0) return;
  for (auto& e : entries) e.second /= n;
}

BowVector make_bow_vector(std::vector<std::pair<WordId, double>> pairs) {
  std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  BowVector v;
  v.entries.reserve(pairs.size());
  for (const auto& p : pairs) {
    if (!v.entries.empty() && v.entries.back().first == p.first)
      v.entries.back().second += p.second;
    else
      v.entries.push_back(p);
  }
  return v;
}

double l1_score(const BowVector& a, const BowVector& b) {
  const double na = a.l1_norm(), nb = b.l1_norm();
  if (na <= 0 || nb <= 0) return 0.0;
  // |x - y| = |x| + |y| - (|x| + |y| - |x - y|): words present in only one
  // vector contribute their full weight, so only shared words need visiting.
  double shared = 0;
  auto ia = a.entries.begin(), ib = b.entries.begin();
  while (ia != a.entries.end() && ib != b.entries.end()) {
    if (ia->first < ib->first) {
      ++ia;
    } else if (ib->first < ia->first) {
      ++ib;
    } else {
      const double x = ia->second / na, y = ib->second / nb;
      shared += std::abs(x) + std::abs(y) - std::abs(x - y);
      ++ia;
      ++ib;
    }
  }
  return std::clamp(0.5 * shared, 0.0, 1.0);
}

const std::vector<std::uint32_t>* FeatureVector::features_of(NodeId node) const {
  const auto it = std::lower_bound(groups.begin(), groups.end(), node,
                                   [](const FeatureGroup& g, NodeId n) { return g.node < n; });
  return it != groups.end() && it->node == node ? &it->features : nullptr;
}

}  // namespace stillslam
