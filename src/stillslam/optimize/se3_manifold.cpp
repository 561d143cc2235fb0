#include "stillslam/optimize/se3_manifold.h"

#include <algorithm>

#include "stillslam/geometry/se3.h"

namespace stillslam {

PoseParams to_pose_params(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q = Eigen::Quaterniond(T.linear()).normalized();
  return {q.x(), q.y(), q.z(), q.w(), T.translation().x(), T.translation().y(), T.translation().z()};
}

Eigen::Isometry3d from_pose_params(const double* params) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(params[3], params[0], params[1], params[2]).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(params[4], params[5], params[6]);
  return T;
}

bool Se3LeftManifold::Plus(const double* x, const double* delta, double* x_plus_delta) const {
  const Eigen::Map<const Eigen::Quaterniond> q(x);
  const Eigen::Map<const Eigen::Vector3d> t(x + 4);
  const Eigen::Map<const Eigen::Vector3d> omega(delta), v(delta + 3);
  const double theta = omega.norm();
  Eigen::Quaterniond dq;
  if (theta < 1e-10) {
    dq = Eigen::Quaterniond(1.0, 0.5 * omega.x(), 0.5 * omega.y(), 0.5 * omega.z());
  } else {
    dq = Eigen::Quaterniond(Eigen::AngleAxisd(theta, omega / theta));
  }
  dq.normalize();
  Eigen::Map<Eigen::Quaterniond> q_out(x_plus_delta);
  Eigen::Map<Eigen::Vector3d> t_out(x_plus_delta + 4);
  q_out = (dq * q).normalized();
  t_out = dq * t + v;
  return true;
}

bool Se3LeftManifold::PlusJacobian(const double*, double* jacobian) const {
  // 7x6 row-major: identity on top, zero last row (see header).
  std::fill(jacobian, jacobian + 42, 0.0);
  for (int i = 0; i < 6; ++i) jacobian[i * 6 + i] = 1.0;
  return true;
}

bool Se3LeftManifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  const Eigen::Isometry3d Ty = from_pose_params(y), Tx = from_pose_params(x);
  const Eigen::Matrix3d dR = Ty.linear() * Tx.linear().transpose();
  const Eigen::Vector3d omega = so3_log(dR);
  const Eigen::Vector3d v = Ty.translation() - dR * Tx.translation();
  for (int i = 0; i < 3; ++i) {
    y_minus_x[i] = omega[i];
    y_minus_x[3 + i] = v[i];
  }
  return true;
}

bool Se3LeftManifold::MinusJacobian(const double*, double* jacobian) const {
  // 6x7 row-major: [I6 0], consistent with PlusJacobian.
  std::fill(jacobian, jacobian + 42, 0.0);
  for (int i = 0; i < 6; ++i) jacobian[i * 7 + i] = 1.0;
  return true;
}

}  // namespace stillslam
