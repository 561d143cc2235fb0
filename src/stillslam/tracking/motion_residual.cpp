#include "stillslam/tracking/motion_residual.h"

#include <cmath>
#include <limits>

namespace stillslam {

double reprojection_residual(const PinholeCamera& camera, const Eigen::Isometry3d& T_cur_prev,
                             const Eigen::Vector2d& prev_pixel, double prev_depth, const Eigen::Vector2d& cur_pixel) {
  const Eigen::Vector3d p_cur = T_cur_prev * camera.unproject(prev_pixel, prev_depth);
  if (p_cur.z() <= 1e-6) return std::numeric_limits<double>::infinity();
  return (camera.project(p_cur) - cur_pixel).norm();
}

double epipolar_residual(const PinholeCamera& camera, const Eigen::Isometry3d& T_cur_prev,
                         const Eigen::Vector2d& prev_pixel, const Eigen::Vector2d& cur_pixel) {
  const Eigen::Vector3d t = T_cur_prev.translation();
  if (t.norm() < 1e-9) return 0.0;
  // Essential matrix E = [t]x R maps a normalized previous ray to the current epipolar line.
  Eigen::Matrix3d tx;
  tx << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  const Eigen::Vector3d line = tx * T_cur_prev.linear() * camera.unproject(prev_pixel, 1.0);
  const Eigen::Vector3d x = camera.unproject(cur_pixel, 1.0);
  // Distance in normalized coordinates, scaled back to pixels by the focal length.
  const double n = std::hypot(line.x(), line.y());
  if (n < 1e-12) return 0.0;
  return std::abs(line.dot(x)) / n * camera.fx();
}

}  // namespace stillslam
