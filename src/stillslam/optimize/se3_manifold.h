#pragma once
// SE3 pose parameter block for Ceres with a left-multiplicative update
//   T <- [Exp(omega), v] * T,  tangent delta = [omega, v],
// stored as 7 doubles: Eigen quaternion coefficients (x, y, z, w) then the
// translation. The cost functions in this folder return their Jacobian with
// respect to the tangent delta directly in the first 6 of the 7 ambient
// columns (column 7 is zero), so PlusJacobian is [I6; 0] and Ceres' chain
// rule yields exactly that tangent Jacobian. Only use this manifold with
// such cost functions (not with autodiff on the ambient parameters).
#include <array>
#include <ceres/manifold.h>
#include <Eigen/Geometry>

namespace stillslam {

using PoseParams = std::array<double, 7>;

PoseParams to_pose_params(const Eigen::Isometry3d& T);
Eigen::Isometry3d from_pose_params(const double* params);

class Se3LeftManifold final : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 7; }
  int TangentSize() const override { return 6; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

}  // namespace stillslam
