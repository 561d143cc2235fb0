#pragma once
// Bundle-adjustment reprojection residuals with analytic Jacobians, whitened
// by sqrt(inv_sigma2): mono [u - u_obs, v - v_obs] and stereo/RGB-D
// [u - u_obs, v - v_obs, u_r - u_r_obs] with u_r = u - bf / z, either as one
// 3-row block or split into the mono block plus [u_r - u_r_obs, 0]
// (StereoRightBaCost): with every block 2 rows, 3-dof points and 6-dof poses
// Ceres uses its fixed-size SchurEliminator<2, 3, 6>; mixed 2- and 3-row
// blocks fall back to the much slower dynamic-size one. Pose blocks use
// Se3LeftManifold (tangent Jacobian in the first 6 ambient columns). Evaluate
// fails (step rejected) when the point is not in front of the camera.
// (The pose-only costs live in pose_residuals.h.)
#include <ceres/sized_cost_function.h>
#include <Eigen/Core>

#include "stillslam/geometry/pinhole_camera.h"

namespace stillslam {

// Points closer than this (camera z, metres) cannot be evaluated: the costs
// fail and the classifications below treat them as outliers.
inline constexpr double kMinCameraDepth = 1e-6;

// Intrinsics copied out of PinholeCamera so costs are self-contained.
struct Intrinsics {
  double fx, fy, cx, cy, bf;
  explicit Intrinsics(const PinholeCamera& c) : fx(c.fx()), fy(c.fy()), cx(c.cx()), cy(c.cy()), bf(c.bf()) {}
};

// Full BA: parameter blocks = pose (7), point (3).
class MonoBaCost final : public ceres::SizedCostFunction<2, 7, 3> {
 public:
  MonoBaCost(const Intrinsics& k, const Eigen::Vector2d& pixel, double inv_sigma2);
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  Intrinsics k_;
  Eigen::Vector2d pixel_;
  double sqrt_info_;
};

class StereoBaCost final : public ceres::SizedCostFunction<3, 7, 3> {
 public:
  StereoBaCost(const Intrinsics& k, const Eigen::Vector2d& pixel, double u_right, double inv_sigma2);
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  Intrinsics k_;
  Eigen::Vector3d observation_;
  double sqrt_info_;
};

// The right-image row of a stereo/RGB-D observation, padded with a zero row
// to the 2 rows of MonoBaCost (see above).
class StereoRightBaCost final : public ceres::SizedCostFunction<2, 7, 3> {
 public:
  StereoRightBaCost(const Intrinsics& k, double u_right, double inv_sigma2);
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  Intrinsics k_;
  double u_right_;
  double sqrt_info_;
};

// Whitened squared error (chi2) and camera-frame depth of one observation,
// for outlier classification outside Ceres. u_right < 0: mono.
struct ReprojectionCheck {
  double chi2;   // +infinity when not in front of the camera
  double depth;
  bool in_front() const { return depth >= kMinCameraDepth; }
};
ReprojectionCheck check_reprojection(const Intrinsics& k, const Eigen::Isometry3d& T_cam_world,
                                     const Eigen::Vector3d& point_world, const Eigen::Vector2d& pixel,
                                     double u_right, double inv_sigma2);

}  // namespace stillslam
