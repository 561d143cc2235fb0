#include "stillslam/io/timestamp_association.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

namespace stillslam {

std::vector<std::pair<std::size_t, std::size_t>> associate_timestamps(const std::vector<double>& a,
                                                                      const std::vector<double>& b,
                                                                      double max_dt) {
  // Candidate pairs within max_dt, found through b sorted by time (the
  // inputs are usually sorted already, but do not rely on it).
  std::vector<std::size_t> b_order(b.size());
  std::iota(b_order.begin(), b_order.end(), std::size_t{0});
  std::stable_sort(b_order.begin(), b_order.end(), [&](std::size_t x, std::size_t y) { return b[x] < b[y]; });
  std::vector<double> b_sorted(b.size());
  for (std::size_t k = 0; k < b.size(); ++k) b_sorted[k] = b[b_order[k]];

  std::vector<std::tuple<double, std::size_t, std::size_t>> candidates;  // (|dt|, ia, ib)
  for (std::size_t ia = 0; ia < a.size(); ++ia) {
    auto k = static_cast<std::size_t>(std::lower_bound(b_sorted.begin(), b_sorted.end(), a[ia] - max_dt) -
                                      b_sorted.begin());
    for (; k < b_sorted.size() && b_sorted[k] < a[ia] + max_dt; ++k) {
      const double dt = std::abs(a[ia] - b_sorted[k]);
      if (dt < max_dt) candidates.emplace_back(dt, ia, b_order[k]);
    }
  }
  std::sort(candidates.begin(), candidates.end());  // ties broken by index: deterministic

  std::vector<bool> used_a(a.size(), false), used_b(b.size(), false);
  std::vector<std::pair<std::size_t, std::size_t>> matches;
  for (const auto& [dt, ia, ib] : candidates) {
    if (used_a[ia] || used_b[ib]) continue;
    used_a[ia] = used_b[ib] = true;
    matches.emplace_back(ia, ib);
  }
  std::sort(matches.begin(), matches.end());
  return matches;
}

}  // namespace stillslam
