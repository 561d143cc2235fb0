#include "stillslam/eval/error_statistics.h"

#include <algorithm>
#include <cmath>

namespace stillslam {

ErrorStatistics compute_statistics(const std::vector<double>& errors) {
  ErrorStatistics stats;
  stats.count = errors.size();
  if (errors.empty()) return stats;
  const double n = static_cast<double>(errors.size());
  double sum = 0, sum_sq = 0;
  for (double e : errors) {
    sum += e;
    sum_sq += e * e;
  }
  stats.mean = sum / n;
  stats.rmse = std::sqrt(sum_sq / n);
  double var = 0;
  for (double e : errors) var += (e - stats.mean) * (e - stats.mean);
  stats.std = std::sqrt(var / n);
  std::vector<double> sorted(errors);
  std::sort(sorted.begin(), sorted.end());
  const std::size_t mid = sorted.size() / 2;
  stats.median = sorted.size() % 2 == 1 ? sorted[mid] : 0.5 * (sorted[mid - 1] + sorted[mid]);
  stats.min = sorted.front();
  stats.max = sorted.back();
  return stats;
}

}  // namespace stillslam
