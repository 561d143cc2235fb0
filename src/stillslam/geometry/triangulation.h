#pragma once
// Two-view triangulation from normalized rays and depth from stereo disparity.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>

namespace stillslam {

struct TriangulationOptions {
  // Reject when the angle between the two viewing rays is too small:
  // cos(parallax) must be below this (0.9998 ~ 1.15 degrees).
  double max_cos_parallax = 0.9998;
  // Depth must be above this in both cameras (cheirality).
  double min_depth = 1e-6;
};

// Linear (DLT, SVD) triangulation. ray1/ray2 are normalized image coordinates
// (x/z, y/z, 1) of the observations — any positive multiple of the viewing
// direction works. Returns the world point, or nothing when the rays are
// (nearly) parallel, the point is behind either camera or the solution is at
// infinity.
std::optional<Eigen::Vector3d> triangulate(const Eigen::Vector3d& ray1,
                                           const Eigen::Isometry3d& T_cam1_world,
                                           const Eigen::Vector3d& ray2,
                                           const Eigen::Isometry3d& T_cam2_world,
                                           const TriangulationOptions& options = {});

// Cosine of the angle between the two viewing rays of a world point.
double cos_parallax(const Eigen::Vector3d& point_world, const Eigen::Isometry3d& T_cam1_world,
                    const Eigen::Isometry3d& T_cam2_world);

// Depth z = bf / (u_left - u_right) for rectified stereo; nothing when the
// disparity is not positive.
std::optional<double> depth_from_disparity(double bf, double u_left, double u_right);

}  // namespace stillslam
