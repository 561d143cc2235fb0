#include "stillslam/optimize/reprojection_costs.h"

#include <cmath>
#include <limits>

#include "stillslam/geometry/se3.h"
#include "stillslam/optimize/se3_manifold.h"

namespace stillslam {
namespace {

using RowMat27 = Eigen::Matrix<double, 2, 7, Eigen::RowMajor>;
using RowMat37 = Eigen::Matrix<double, 3, 7, Eigen::RowMajor>;
using RowMat23 = Eigen::Matrix<double, 2, 3, Eigen::RowMajor>;
using RowMat33 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

struct Projected {
  Eigen::Vector3d p_cam;
  Eigen::Matrix3d R;  // rotation of T_cam_world
};

Projected transform(const double* pose, const Eigen::Vector3d& point_world) {
  const Eigen::Map<const Eigen::Quaterniond> q(pose);
  const Eigen::Map<const Eigen::Vector3d> t(pose + 4);
  // The manifold keeps q unit length, so no renormalization here.
  const Eigen::Matrix3d R = q.toRotationMatrix();
  return {R * point_world + t, R};
}

// d(u, v[, u_r]) / d p_cam, times sqrt_info.
template <int N>
Eigen::Matrix<double, N, 3> projection_jacobian(const Intrinsics& k, const Eigen::Vector3d& p, double s) {
  const double iz = 1.0 / p.z(), iz2 = iz * iz;
  Eigen::Matrix<double, N, 3> J;
  J(0, 0) = k.fx * iz;
  J(0, 1) = 0;
  J(0, 2) = -k.fx * p.x() * iz2;
  J(1, 0) = 0;
  J(1, 1) = k.fy * iz;
  J(1, 2) = -k.fy * p.y() * iz2;
  if constexpr (N == 3) {
    J(2, 0) = J(0, 0);
    J(2, 1) = 0;
    J(2, 2) = J(0, 2) + k.bf * iz2;
  }
  return s * J;
}

// d p_cam / d [omega, v] for the left update: [-[p_cam]x, I].
template <int N, typename Out>
void fill_pose_jacobian(const Eigen::Matrix<double, N, 3>& Jp, const Eigen::Vector3d& p, Out& J) {
  J.template leftCols<3>() = -Jp * skew(p);
  J.template middleCols<3>(3) = Jp;
  J.col(6).setZero();
}

}  // namespace

MonoBaCost::MonoBaCost(const Intrinsics& k, const Eigen::Vector2d& pixel, double inv_sigma2)
    : k_(k), pixel_(pixel), sqrt_info_(std::sqrt(inv_sigma2)) {}

bool MonoBaCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const Projected pr = transform(parameters[0], Eigen::Map<const Eigen::Vector3d>(parameters[1]));
  const Eigen::Vector3d& p = pr.p_cam;
  if (p.z() < kMinCameraDepth) return false;
  const double iz = 1.0 / p.z();
  residuals[0] = sqrt_info_ * (k_.fx * p.x() * iz + k_.cx - pixel_.x());
  residuals[1] = sqrt_info_ * (k_.fy * p.y() * iz + k_.cy - pixel_.y());
  if (jacobians && (jacobians[0] || jacobians[1])) {
    const Eigen::Matrix<double, 2, 3> Jp = projection_jacobian<2>(k_, p, sqrt_info_);
    if (jacobians[0]) {
      Eigen::Map<RowMat27> J(jacobians[0]);
      fill_pose_jacobian<2>(Jp, p, J);
    }
    if (jacobians[1]) Eigen::Map<RowMat23>{jacobians[1]} = Jp * pr.R;
  }
  return true;
}

StereoBaCost::StereoBaCost(const Intrinsics& k, const Eigen::Vector2d& pixel, double u_right, double inv_sigma2)
    : k_(k), observation_(pixel.x(), pixel.y(), u_right), sqrt_info_(std::sqrt(inv_sigma2)) {}

bool StereoBaCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const Projected pr = transform(parameters[0], Eigen::Map<const Eigen::Vector3d>(parameters[1]));
  const Eigen::Vector3d& p = pr.p_cam;
  if (p.z() < kMinCameraDepth) return false;
  const double iz = 1.0 / p.z();
  const double u = k_.fx * p.x() * iz + k_.cx;
  residuals[0] = sqrt_info_ * (u - observation_.x());
  residuals[1] = sqrt_info_ * (k_.fy * p.y() * iz + k_.cy - observation_.y());
  residuals[2] = sqrt_info_ * (u - k_.bf * iz - observation_.z());
  if (jacobians && (jacobians[0] || jacobians[1])) {
    const Eigen::Matrix<double, 3, 3> Jp = projection_jacobian<3>(k_, p, sqrt_info_);
    if (jacobians[0]) {
      Eigen::Map<RowMat37> J(jacobians[0]);
      fill_pose_jacobian<3>(Jp, p, J);
    }
    if (jacobians[1]) Eigen::Map<RowMat33>{jacobians[1]} = Jp * pr.R;
  }
  return true;
}

StereoRightBaCost::StereoRightBaCost(const Intrinsics& k, double u_right, double inv_sigma2)
    : k_(k), u_right_(u_right), sqrt_info_(std::sqrt(inv_sigma2)) {}

bool StereoRightBaCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const Projected pr = transform(parameters[0], Eigen::Map<const Eigen::Vector3d>(parameters[1]));
  const Eigen::Vector3d& p = pr.p_cam;
  if (p.z() < kMinCameraDepth) return false;
  const double iz = 1.0 / p.z();
  residuals[0] = sqrt_info_ * (k_.fx * p.x() * iz + k_.cx - k_.bf * iz - u_right_);
  residuals[1] = 0;
  if (jacobians && (jacobians[0] || jacobians[1])) {
    // Row 3 of the stereo projection Jacobian, then a zero row.
    const Eigen::Matrix<double, 3, 3> J3 = projection_jacobian<3>(k_, p, sqrt_info_);
    Eigen::Matrix<double, 2, 3> Jp = Eigen::Matrix<double, 2, 3>::Zero();
    Jp.row(0) = J3.row(2);
    if (jacobians[0]) {
      Eigen::Map<RowMat27> J(jacobians[0]);
      fill_pose_jacobian<2>(Jp, p, J);
    }
    if (jacobians[1]) Eigen::Map<RowMat23>{jacobians[1]} = Jp * pr.R;
  }
  return true;
}

ReprojectionCheck check_reprojection(const Intrinsics& k, const Eigen::Isometry3d& T_cam_world,
                                     const Eigen::Vector3d& point_world, const Eigen::Vector2d& pixel,
                                     double u_right, double inv_sigma2) {
  const Eigen::Vector3d p = T_cam_world * point_world;
  if (p.z() < kMinCameraDepth) return {std::numeric_limits<double>::infinity(), p.z()};
  const double iz = 1.0 / p.z();
  const double u = k.fx * p.x() * iz + k.cx;
  const double eu = u - pixel.x(), ev = k.fy * p.y() * iz + k.cy - pixel.y();
  double e2 = eu * eu + ev * ev;
  if (u_right >= 0) {
    const double er = u - k.bf * iz - u_right;
    e2 += er * er;
  }
  return {e2 * inv_sigma2, p.z()};
}

}  // namespace stillslam
