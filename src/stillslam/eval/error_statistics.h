#pragma once
// Summary statistics of an error series, defined as in evo (std is the
// population standard deviation, median averages the two middle values).
#include <cstddef>
#include <limits>
#include <vector>

namespace stillslam {

// An empty series has no statistics: count 0 and NaN values (written as null
// in JSON, "n/a" in tables), so no reader mistakes it for a perfect 0.
struct ErrorStatistics {
  std::size_t count = 0;
  double rmse = std::numeric_limits<double>::quiet_NaN();
  double mean = std::numeric_limits<double>::quiet_NaN();
  double median = std::numeric_limits<double>::quiet_NaN();
  double std = std::numeric_limits<double>::quiet_NaN();
  double min = std::numeric_limits<double>::quiet_NaN();
  double max = std::numeric_limits<double>::quiet_NaN();

  bool empty() const { return count == 0; }
};

// Count 0 and NaN values for an empty series.
ErrorStatistics compute_statistics(const std::vector<double>& errors);

}  // namespace stillslam
