#pragma once
// The 1-minute load average, printed by benchmarks so a reader can tell a
// figure from a shared, busy machine.
#include <fstream>

namespace stillslam {

inline double load_average() {
  std::ifstream in("/proc/loadavg");
  double l = 0;
  in >> l;
  return l;
}

}  // namespace stillslam
