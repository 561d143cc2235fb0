#include "stillslam/eval/association.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <tuple>

#include "stillslam/core/error.h"
#include "stillslam/core/option_check.h"
#include "stillslam/io/timestamp_association.h"

namespace stillslam {
namespace {

// Index of the last occurrence of each distinct stamp, sorted by stamp.
std::vector<std::size_t> unique_sorted_last(const std::vector<double>& stamps) {
  std::vector<std::size_t> order(stamps.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return stamps[a] < stamps[b]; });
  std::vector<std::size_t> kept;
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k + 1 < order.size() && stamps[order[k + 1]] == stamps[order[k]]) continue;  // a later duplicate wins
    kept.push_back(order[k]);
  }
  return kept;
}

std::vector<IndexPair> associate_greedy(const std::vector<double>& gt, const std::vector<double>& est,
                                        double max_dt, double offset) {
  // associate.py sorts candidates by (|dt|, gt stamp, est stamp); with both
  // lists unique and sorted by stamp, index order is stamp order, so the
  // dataset readers' greedy rule gives the same pairs.
  const auto gt_ids = unique_sorted_last(gt);
  const auto est_ids = unique_sorted_last(est);
  std::vector<double> gt_sorted(gt_ids.size()), est_shifted(est_ids.size());
  for (std::size_t k = 0; k < gt_ids.size(); ++k) gt_sorted[k] = gt[gt_ids[k]];
  for (std::size_t k = 0; k < est_ids.size(); ++k) est_shifted[k] = est[est_ids[k]] + offset;
  std::vector<IndexPair> pairs;
  for (const auto& [g, e] : associate_timestamps(gt_sorted, est_shifted, max_dt)) pairs.push_back({gt_ids[g], est_ids[e]});
  std::sort(pairs.begin(), pairs.end(), [&](const IndexPair& x, const IndexPair& y) {
    return std::tie(gt[x.gt], est[x.est]) < std::tie(gt[y.gt], est[y.est]);
  });
  return pairs;
}

// For each of `short_stamps`, the first index of the minimum |dt| in `long_stamps`.
std::vector<std::pair<std::size_t, std::size_t>> nearest_matches(const std::vector<double>& short_stamps,
                                                                 const std::vector<double>& long_stamps,
                                                                 double max_dt, double long_offset) {
  std::vector<std::pair<std::size_t, std::size_t>> matches;
  if (long_stamps.empty()) return matches;
  // Sorted view of the long stamps; ties resolved to the smallest original index as argmin does.
  std::vector<std::size_t> order(long_stamps.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return long_stamps[a] < long_stamps[b]; });
  std::vector<double> sorted(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) sorted[k] = long_stamps[order[k]] + long_offset;
  for (std::size_t s = 0; s < short_stamps.size(); ++s) {
    const double t = short_stamps[s];
    const auto pos = static_cast<std::size_t>(std::lower_bound(sorted.begin(), sorted.end(), t) - sorted.begin());
    double best_dt = std::numeric_limits<double>::infinity();
    if (pos > 0) best_dt = std::abs(sorted[pos - 1] - t);
    if (pos < sorted.size()) best_dt = std::min(best_dt, std::abs(sorted[pos] - t));
    // Every stamp at exactly best_dt sits next to pos; keep the smallest original index.
    std::size_t best = std::numeric_limits<std::size_t>::max();
    for (std::size_t k = pos; k > 0 && std::abs(sorted[k - 1] - t) == best_dt; --k) best = std::min(best, order[k - 1]);
    for (std::size_t k = pos; k < sorted.size() && std::abs(sorted[k] - t) == best_dt; ++k) best = std::min(best, order[k]);
    if (best_dt <= max_dt) matches.emplace_back(s, best);
  }
  return matches;
}

std::vector<IndexPair> associate_nearest(const std::vector<double>& gt, const std::vector<double>& est,
                                         double max_dt, double offset) {
  std::vector<IndexPair> pairs;
  const bool est_longer = est.size() > gt.size();
  if (est_longer) {
    for (const auto& [g, e] : nearest_matches(gt, est, max_dt, offset)) pairs.push_back({g, e});
  } else {
    std::vector<double> est_shifted(est);
    for (double& t : est_shifted) t += offset;
    for (const auto& [e, g] : nearest_matches(est_shifted, gt, max_dt, 0.0)) pairs.push_back({g, e});
  }
  std::stable_sort(pairs.begin(), pairs.end(), [&](const IndexPair& x, const IndexPair& y) { return gt[x.gt] < gt[y.gt]; });
  return pairs;
}

}  // namespace

AssociationMethod parse_association_method(const std::string& name) {
  if (name == "tum" || name == "greedy") return AssociationMethod::Greedy;
  if (name == "nearest" || name == "evo") return AssociationMethod::Nearest;
  throw Error("unknown association method '" + name + "'; use tum (greedy, as TUM associate.py) or nearest (as evo)");
}

std::string to_string(AssociationMethod method) {
  return method == AssociationMethod::Greedy ? "tum" : "nearest";
}

double AssociationOptions::effective_max_dt() const {
  if (max_dt > 0) return max_dt;
  return method == AssociationMethod::Greedy ? 0.02 : 0.01;
}

void AssociationOptions::check() const {
  if (!(max_dt >= 0) || !std::isfinite(max_dt)) {
    throw OptionError("AssociationOptions.max_dt", option_check::text(max_dt),
                      "must be a finite number >= 0 (0 picks the method's default)");
  }
  if (!std::isfinite(offset)) {
    throw OptionError("AssociationOptions.offset", option_check::text(offset), "must be a finite number of seconds");
  }
}

std::vector<IndexPair> associate(const std::vector<double>& gt_stamps, const std::vector<double>& est_stamps,
                                 const AssociationOptions& options) {
  options.check();
  const double max_dt = options.effective_max_dt();
  if (options.method == AssociationMethod::Greedy) return associate_greedy(gt_stamps, est_stamps, max_dt, options.offset);
  return associate_nearest(gt_stamps, est_stamps, max_dt, options.offset);
}

}  // namespace stillslam
