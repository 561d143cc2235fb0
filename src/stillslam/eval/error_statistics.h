#pragma once
// Summary statistics of an error series, defined as in evo (std is the
// population standard deviation, median averages the two middle values).
#include <cstddef>
#include <vector>

namespace stillslam {

struct ErrorStatistics {
  std::size_t count = 0;
  double rmse = 0;
  double mean = 0;
  double median = 0;
  double std = 0;
  double min = 0;
  double max = 0;
};

// All zero for an empty series.
ErrorStatistics compute_statistics(const std::vector<double>& errors);

}  // namespace stillslam
