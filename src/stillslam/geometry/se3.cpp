#include "stillslam/geometry/se3.h"

#include <algorithm>
#include <cmath>

namespace stillslam {

Eigen::Matrix3d skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d S;
  S << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return S;
}

Eigen::Matrix3d so3_exp(const Eigen::Vector3d& omega) {
  const double theta = omega.norm();
  if (theta < 1e-10) return Eigen::Matrix3d::Identity() + skew(omega);
  return Eigen::AngleAxisd(theta, omega / theta).toRotationMatrix();
}

Eigen::Vector3d so3_log(const Eigen::Matrix3d& R) {
  // Via the quaternion: stable near 0 and near pi, unlike acos of the trace.
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const double vn = q.vec().norm();
  if (vn < 1e-12) return 2.0 * q.vec();  // first order: theta ~ 2|v|
  const double theta = 2.0 * std::atan2(vn, q.w());
  return q.vec() * (theta / vn);
}

Eigen::Matrix3d so3_left_jacobian(const Eigen::Vector3d& omega) {
  const double theta = omega.norm();
  const Eigen::Matrix3d W = skew(omega);
  if (theta < 1e-6) return Eigen::Matrix3d::Identity() + 0.5 * W + W * W / 6.0;
  const double t2 = theta * theta;
  return Eigen::Matrix3d::Identity() + (1.0 - std::cos(theta)) / t2 * W +
         (theta - std::sin(theta)) / (t2 * theta) * W * W;
}

Eigen::Isometry3d se3_exp(const Vector6d& xi) {
  const Eigen::Vector3d omega = xi.head<3>(), v = xi.tail<3>();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = so3_exp(omega);
  T.translation() = so3_left_jacobian(omega) * v;
  return T;
}

Vector6d se3_log(const Eigen::Isometry3d& T) {
  const Eigen::Vector3d omega = so3_log(T.linear());
  Vector6d xi;
  xi.head<3>() = omega;
  // J is invertible for theta < 2 pi; the log keeps theta <= pi.
  xi.tail<3>() = so3_left_jacobian(omega).inverse() * T.translation();
  return xi;
}

double rotation_angle(const Eigen::Matrix3d& R) {
  return so3_log(R).norm();
}

Eigen::Isometry3d interpolate(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double t) {
  const Eigen::Quaterniond qa(a.linear()), qb(b.linear());
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = qa.slerp(t, qb).normalized().toRotationMatrix();
  out.translation() = (1.0 - t) * a.translation() + t * b.translation();
  return out;
}

Eigen::Isometry3d normalized(const Eigen::Isometry3d& T) {
  Eigen::Isometry3d out = T;
  out.linear() = Eigen::Quaterniond(T.linear()).normalized().toRotationMatrix();
  return out;
}

Eigen::Isometry3d Sim3::rigid() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = t;
  return T;
}

Eigen::Matrix4d Sim3::matrix() const {
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  M.topLeftCorner<3, 3>() = s * R;
  M.topRightCorner<3, 1>() = t;
  return M;
}

}  // namespace stillslam
