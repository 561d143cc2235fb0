#pragma once
// Small Lie-group helpers on Eigen types. Tangent vectors of SE3 are 6-vectors
// ordered [omega (rotation, rad), v (translation)] everywhere in stillslam;
// se3_exp/se3_log are the exact group exponential/logarithm (v is not the
// translation itself unless omega is zero).
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace stillslam {

using Vector6d = Eigen::Matrix<double, 6, 1>;

Eigen::Matrix3d skew(const Eigen::Vector3d& w);

// Rodrigues: rotation of angle |omega| about omega.
Eigen::Matrix3d so3_exp(const Eigen::Vector3d& omega);
// Inverse of so3_exp; the angle is in [0, pi].
Eigen::Vector3d so3_log(const Eigen::Matrix3d& R);
// Left Jacobian of SO3 (maps v to the translation of se3_exp([omega, v])).
Eigen::Matrix3d so3_left_jacobian(const Eigen::Vector3d& omega);

// xi = [omega, v].
Eigen::Isometry3d se3_exp(const Vector6d& xi);
Vector6d se3_log(const Eigen::Isometry3d& T);

// Rotation angle in radians, in [0, pi].
double rotation_angle(const Eigen::Matrix3d& R);
inline double rotation_angle(const Eigen::Isometry3d& T) { return rotation_angle(T.linear()); }
inline double rotation_angle_deg(const Eigen::Isometry3d& T) {
  return rotation_angle(T) * 180.0 / 3.14159265358979323846;
}

// Geodesic-free practical interpolation: slerp on rotation, linear on
// translation; t = 0 gives a, t = 1 gives b.
Eigen::Isometry3d interpolate(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double t);

// Re-orthonormalize the rotation block (after long chains of products).
Eigen::Isometry3d normalized(const Eigen::Isometry3d& T);

// Similarity transform x -> s * R * x + t (for loop closing / map merging and
// monocular scale drift). Naming as poses: Sim3 S_a_b maps b-frame points to a.
struct Sim3 {
  double s = 1.0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();

  Sim3() = default;
  Sim3(double scale, const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation)
      : s(scale), R(rotation), t(translation) {}
  explicit Sim3(const Eigen::Isometry3d& T) : s(1.0), R(T.linear()), t(T.translation()) {}

  Eigen::Vector3d operator*(const Eigen::Vector3d& x) const { return s * (R * x) + t; }
  Sim3 operator*(const Sim3& o) const { return {s * o.s, R * o.R, s * (R * o.t) + t}; }
  Sim3 inverse() const {
    const Eigen::Matrix3d Rt = R.transpose();
    return {1.0 / s, Rt, -(Rt * t) / s};
  }
  // [R, t] with the scale dropped (t is kept as is).
  Eigen::Isometry3d rigid() const;
  Eigen::Matrix4d matrix() const;
};

}  // namespace stillslam
