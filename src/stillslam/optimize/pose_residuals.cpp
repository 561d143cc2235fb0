#include "stillslam/optimize/pose_residuals.h"

#include <cmath>

#include "stillslam/geometry/se3.h"

namespace stillslam {
namespace {

// In place: r <- g(n) r and J <- g J + (g'(n) / n) r (r^T J) for n = |r| > delta,
// with g(n) = sqrt(2 delta n - delta^2) / n (see header). J is N x 6 row-major.
template <int N>
void apply_huber(double delta, double* r_ptr, double* J_ptr) {
  Eigen::Map<Eigen::Matrix<double, N, 1>> r(r_ptr);
  const double n = r.norm();
  if (n <= delta) return;
  const double root = std::sqrt(2.0 * delta * n - delta * delta);
  const double g = root / n;
  if (J_ptr) {
    const double dg = (delta / root - g) / n;
    Eigen::Map<Eigen::Matrix<double, N, 6, Eigen::RowMajor>> J(J_ptr);
    const Eigen::Matrix<double, 1, 6> rtJ = r.transpose() * J;
    J = g * J + (dg / n) * r * rtJ;
  }
  r *= g;
}

}  // namespace

PoseResiduals::PoseResiduals(const Intrinsics& k, const Eigen::Isometry3d& anchor,
                             const std::vector<PoseObservation>& observations, const std::vector<bool>& stereo,
                             std::vector<std::size_t> active, const PoseResidualsOptions& options)
    : k_(k),
      anchor_(anchor),
      observations_(observations),
      stereo_(stereo),
      active_(std::move(active)),
      options_(options) {
  int rows = 0;
  for (std::size_t i : active_) rows += stereo_[i] ? 3 : 2;
  set_num_residuals(rows);
  mutable_parameter_block_sizes()->push_back(6);
}

Eigen::Isometry3d PoseResiduals::pose(const double* delta) const {
  Eigen::Isometry3d D = Eigen::Isometry3d::Identity();
  D.linear() = so3_exp(Eigen::Vector3d(delta[0], delta[1], delta[2]));
  D.translation() = Eigen::Vector3d(delta[3], delta[4], delta[5]);
  return normalized(D * anchor_);
}

bool PoseResiduals::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const double* delta = parameters[0];
  const Eigen::Vector3d omega(delta[0], delta[1], delta[2]);
  const Eigen::Vector3d v(delta[3], delta[4], delta[5]);
  const Eigen::Matrix3d dR = so3_exp(omega);
  const Eigen::Matrix3d R = dR * anchor_.linear();
  const Eigen::Vector3d t = dR * anchor_.translation() + v;
  double* J_out = jacobians ? jacobians[0] : nullptr;
  // p = Exp(omega) q + v  =>  dp/domega = -[p - v]x Jl(omega), dp/dv = I.
  const Eigen::Matrix3d Jl = J_out ? so3_left_jacobian(omega) : Eigen::Matrix3d::Identity();

  int row = 0;
  for (std::size_t i : active_) {
    const PoseObservation& o = observations_[i];
    const bool stereo = stereo_[i];
    const Eigen::Vector3d p = R * o.point_world + t;
    if (p.z() < kMinCameraDepth) return false;
    const double s = std::sqrt(o.inv_sigma2);
    const double iz = 1.0 / p.z();
    const double u = k_.fx * p.x() * iz + k_.cx;
    double* r = residuals + row;
    r[0] = s * (u - o.pixel.x());
    r[1] = s * (k_.fy * p.y() * iz + k_.cy - o.pixel.y());
    if (stereo) r[2] = s * (u - k_.bf * iz - o.u_right);
    double* J_rows = J_out ? J_out + 6 * row : nullptr;
    if (J_rows) {
      // Whitened projection Jacobian rows a = d(u, v[, u_r]) / dp, chained to
      // delta: row_omega = -a^T [w]x Jl = (w x a)^T Jl with w = p - v, row_v = a^T.
      const double a00 = s * k_.fx * iz, a02 = -s * k_.fx * p.x() * iz * iz;
      const double a11 = s * k_.fy * iz, a12 = -s * k_.fy * p.y() * iz * iz;
      const Eigen::Vector3d w = p - v;
      const int dim = stereo ? 3 : 2;
      for (int a = 0; a < dim; ++a) {
        Eigen::Vector3d jp;
        if (a == 0) {
          jp = {a00, 0.0, a02};
        } else if (a == 1) {
          jp = {0.0, a11, a12};
        } else {
          jp = {a00, 0.0, a02 + s * k_.bf * iz * iz};
        }
        const Eigen::Vector3d jw = Jl.transpose() * w.cross(jp);
        double* out = J_rows + 6 * a;
        out[0] = jw.x();
        out[1] = jw.y();
        out[2] = jw.z();
        out[3] = jp.x();
        out[4] = jp.y();
        out[5] = jp.z();
      }
    }
    if (options_.robust) {
      if (stereo) {
        apply_huber<3>(options_.huber_stereo, r, J_rows);
      } else {
        apply_huber<2>(options_.huber_mono, r, J_rows);
      }
    }
    row += stereo ? 3 : 2;
  }
  return true;
}

}  // namespace stillslam
