#pragma once
// CPU time of the whole process (all threads: tracking, segmentation,
// local mapping, loading), in seconds.
#include <ctime>

namespace stillslam {

inline double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

}  // namespace stillslam
