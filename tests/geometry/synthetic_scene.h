#pragma once
// Deterministic synthetic scenes shared by the geometry and optimize tests.
#include <Eigen/Geometry>
#include <random>
#include <vector>

#include "stillslam/geometry/camera_calibration.h"
#include "stillslam/geometry/se3.h"

namespace stillslam::testing {

inline CameraCalibration tum_like_calibration() {
  return pinhole_calibration(517.3, 516.5, 318.6, 255.3, 640, 480);
}

// Camera looking down +z of the world from `center`, rotated by small angles.
inline Eigen::Isometry3d camera_pose(const Eigen::Vector3d& center, const Eigen::Vector3d& omega) {
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();
  T_world_cam.linear() = so3_exp(omega);
  T_world_cam.translation() = center;
  return T_world_cam.inverse();  // T_cam_world
}

// Points spread in a box in front of the world origin (z in [2, 6]).
inline std::vector<Eigen::Vector3d> random_points(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> xy(-2.0, 2.0), z(2.0, 6.0);
  std::vector<Eigen::Vector3d> pts(static_cast<std::size_t>(n));
  for (auto& p : pts) p = {xy(rng), xy(rng), z(rng)};
  return pts;
}

inline double translation_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.inverse().translation() - b.inverse().translation()).norm();
}
inline double rotation_error_deg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return rotation_angle_deg(a * b.inverse());
}

}  // namespace stillslam::testing
