#include "stillslam/benchmark/plot_geometry.h"

#include <algorithm>
#include <limits>

namespace stillslam {

std::array<int, 2> spread_axes(const Trajectory& trajectory) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const StampedPose& p : trajectory) mean += p.T_world_cam.translation();
  mean /= static_cast<double>(std::max<std::size_t>(trajectory.size(), 1));
  Eigen::Vector3d var = Eigen::Vector3d::Zero();
  for (const StampedPose& p : trajectory) var += (p.T_world_cam.translation() - mean).cwiseAbs2();
  int dropped = 0;
  var.minCoeff(&dropped);
  std::array<int, 2> axes{};
  for (int a = 0, k = 0; a < 3; ++a) {
    if (a != dropped) axes[k++] = a;
  }
  return axes;
}

double stamp_gap_limit(const std::vector<double>& stamps) {
  if (stamps.size() < 3) return std::numeric_limits<double>::infinity();
  std::vector<double> steps;
  for (std::size_t k = 1; k < stamps.size(); ++k) steps.push_back(stamps[k] - stamps[k - 1]);
  std::nth_element(steps.begin(), steps.begin() + static_cast<long>(steps.size() / 2), steps.end());
  return std::max(10.0 * steps[steps.size() / 2], 0.5);
}

}  // namespace stillslam
