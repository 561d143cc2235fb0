#include "stillslam/tracking/sparse_view.h"

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
                           const std::vector<std::uint64_t>& group, double gain, int velocity_frames) {
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
    centres[i] = filter.step(centres[i - 1], start_velocity, centres[i], 1);
  }
}

}  // namespace stillslam
