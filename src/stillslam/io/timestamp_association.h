#pragma once
// Pairs two timestamp lists the way TUM's associate.py does: every candidate
// pair with |a - b| < max_dt, taken greedily by smallest difference, each
// element used at most once. Used for TUM rgb/depth and EuRoC cam0/cam1.
#include <cstddef>
#include <utility>
#include <vector>

namespace stillslam {

// Returns (index in a, index in b) pairs sorted by index in a.
std::vector<std::pair<std::size_t, std::size_t>> associate_timestamps(const std::vector<double>& a,
                                                                      const std::vector<double>& b,
                                                                      double max_dt);

}  // namespace stillslam
