#include "stillslam/tracking/sparse_view.h"

#include <Eigen/Eigenvalues>

#include <algorithm>

#include "stillslam/core/option_check.h"
#include "stillslam/segmentation/dynamic_mask.h"

namespace stillslam {

void SparseViewOptions::check() const {
  using namespace option_check;
  in_range("SparseViewOptions.masked_share", masked_share, 0.0, 1.0);
  in_range("SparseViewOptions.inliers", inliers, 0, 100000);
  in_range("SparseViewOptions.tracked_weight", tracked_weight, 0.0, 1.0);
  in_range("SparseViewOptions.smooth_frames", smooth_frames, 0, 100);
  in_range("SparseViewOptions.filter_gain", filter_gain, 0.0, 1.0);
  in_range("SparseViewOptions.filter_frames", filter_frames, 1, 100);
  in_range("SparseViewOptions.filter_axes", filter_axes, 1, 3);
  in_range("SparseViewOptions.keyframe_prior_sigma", keyframe_prior_sigma, 0.0, 1.0);
}

double masked_share(const Frame& frame) { return mask_coverage(frame.dynamic_mask()); }

bool is_sparse_view(const Frame& frame, const SparseViewOptions& options) {
  return options.enabled && !frame.dynamic_mask().empty() && masked_share(frame) >= options.masked_share;
}

Eigen::Isometry3d blend_poses(const Eigen::Isometry3d& predicted, const Eigen::Isometry3d& tracked,
                              double tracked_weight) {
  // Camera centres blend along the path, not through the world origin.
  const Eigen::Isometry3d p = predicted.inverse(), t = tracked.inverse();
  const Eigen::Quaterniond qp(p.rotation()), qt(t.rotation());
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = qp.slerp(tracked_weight, qt).normalized().toRotationMatrix();
  out.translation() = (1.0 - tracked_weight) * p.translation() + tracked_weight * t.translation();
  return out.inverse();
}

void smooth_sparse_centres(std::vector<Eigen::Vector3d>& centres, const std::vector<bool>& sparse,
                           const std::vector<std::uint64_t>& group, int half_window) {
  if (half_window <= 0) return;
  const std::vector<Eigen::Vector3d> given = centres;
  const auto n = static_cast<std::ptrdiff_t>(given.size());
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    if (!sparse[static_cast<std::size_t>(i)]) continue;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int count = 0;
    for (std::ptrdiff_t j = std::max<std::ptrdiff_t>(0, i - half_window); j <= std::min(n - 1, i + half_window); ++j) {
      if (group[static_cast<std::size_t>(j)] != group[static_cast<std::size_t>(i)]) continue;
      sum += given[static_cast<std::size_t>(j)];
      ++count;
    }
    centres[static_cast<std::size_t>(i)] = sum / count;
  }
}

CentreFilter::CentreFilter(double gain) : alpha_(gain), beta_(gain * gain / (2.0 - gain)) {}

Eigen::Vector3d CentreFilter::step(const Eigen::Vector3d& last, const Eigen::Vector3d& start_velocity,
                                   const Eigen::Vector3d& tracked, int steps) {
  if (!velocity_) velocity_ = start_velocity;
  const double n = std::max(1, steps);
  const Eigen::Vector3d predicted = last + n * *velocity_;
  const Eigen::Vector3d innovation = tracked - predicted;
  *velocity_ += beta_ / n * innovation;
  return predicted + alpha_ * innovation;
}

void filter_sparse_centres(std::vector<Eigen::Vector3d>& centres, const std::vector<bool>& sparse,
                           const std::vector<std::uint64_t>& group, double gain, int velocity_frames,
                           const std::vector<Eigen::Matrix3d>& projections) {
  if (gain <= 0) return;
  CentreFilter filter(gain);
  for (std::size_t i = 0; i < centres.size(); ++i) {
    if (!sparse[i] || i == 0 || group[i - 1] != group[i]) {
      filter.stop();
      continue;
    }
    // The run's start: the mean motion over up to velocity_frames centres before it.
    std::size_t first = i - 1;
    while (first > 0 && i - 1 - (first - 1) <= static_cast<std::size_t>(velocity_frames) &&
           group[first - 1] == group[i]) {
      --first;
    }
    const Eigen::Vector3d start_velocity =
        first < i - 1 ? Eigen::Vector3d((centres[i - 1] - centres[first]) / static_cast<double>(i - 1 - first))
                      : Eigen::Vector3d::Zero();
    const Eigen::Vector3d filtered = filter.step(centres[i - 1], start_velocity, centres[i], 1);
    const bool all_axes = projections.empty() || projections[i] == Eigen::Matrix3d::Identity();
    centres[i] = all_axes ? filtered : Eigen::Vector3d(centres[i] + projections[i] * (filtered - centres[i]));
  }
}

Eigen::Matrix3d centre_covariance(const PinholeCamera& camera, const Eigen::Isometry3d& T_cam_world,
                                  const std::vector<PoseObservation>& observations) {
  // Perturbation [omega, dc]: R' = Exp(omega) R, C' = C + dc, so a point in
  // the camera moves by dp = -[p]x omega - R dc.
  const Eigen::Matrix3d R = T_cam_world.linear();
  Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
  int used = 0;
  for (const PoseObservation& o : observations) {
    const Eigen::Vector3d p = T_cam_world * o.point_world;
    if (p.z() <= 0) continue;
    Eigen::Matrix<double, 3, 6> Jp;
    Jp.leftCols<3>() << 0, p.z(), -p.y(), -p.z(), 0, p.x(), p.y(), -p.x(), 0;  // -[p]x
    Jp.rightCols<3>() = -R;
    const double iz = 1.0 / p.z(), iz2 = iz * iz;
    Eigen::Matrix<double, 3, 3> Jproj = Eigen::Matrix3d::Zero();
    Jproj.row(0) << camera.fx() * iz, 0, -camera.fx() * p.x() * iz2;
    Jproj.row(1) << 0, camera.fy() * iz, -camera.fy() * p.y() * iz2;
    const int rows = o.u_right >= 0 && camera.bf() > 0 ? 3 : 2;
    if (rows == 3) Jproj.row(2) << camera.fx() * iz, 0, -camera.fx() * p.x() * iz2 + camera.bf() * iz2;
    const Eigen::Matrix<double, 3, 6> J = Jproj * Jp;
    H += o.inv_sigma2 * J.topRows(rows).transpose() * J.topRows(rows);
    ++used;
  }
  if (used < 3) return Eigen::Matrix3d::Zero();
  const Eigen::Matrix3d Hrr = H.topLeftCorner<3, 3>(), Hrc = H.topRightCorner<3, 3>(), Hcc = H.bottomRightCorner<3, 3>();
  const Eigen::Matrix3d info = Hcc - Hrc.transpose() * Hrr.ldlt().solve(Hrc);
  return info.ldlt().solve(Eigen::Matrix3d::Identity());
}

Eigen::Matrix3d weak_axes_projection(const Eigen::Matrix3d& covariance, int axes) {
  if (axes >= 3 || covariance.isZero()) return Eigen::Matrix3d::Identity();
  // Eigenvalues ascending: the last `axes` columns are the least certain directions.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (covariance + covariance.transpose()));
  const Eigen::MatrixXd weak = eig.eigenvectors().rightCols(std::max(0, axes));
  return weak * weak.transpose();
}

}  // namespace stillslam
