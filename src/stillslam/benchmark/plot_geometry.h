#pragma once
// Choices shared by the benchmark plots and the HTML run report: which two
// world axes show a trajectory from above, and where a stamped series has a
// hole (tracking lost) so no line is drawn across it.
#include <array>
#include <vector>

#include "stillslam/core/trajectory.h"

namespace stillslam {

// The two world axes along which `trajectory` spreads most (x=0, y=1, z=2), in order.
std::array<int, 2> spread_axes(const Trajectory& trajectory);

// A step over 10x the median step and over 0.5 s; infinity for fewer than 3 stamps.
double stamp_gap_limit(const std::vector<double>& stamps);

}  // namespace stillslam
