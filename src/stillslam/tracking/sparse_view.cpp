#include "stillslam/tracking/sparse_view.h"

#include "stillslam/core/option_check.h"
#include "stillslam/segmentation/dynamic_mask.h"

namespace stillslam {

void SparseViewOptions::check() const {
  using namespace option_check;
  in_range("SparseViewOptions.masked_share", masked_share, 0.0, 1.0);
  in_range("SparseViewOptions.inliers", inliers, 0, 100000);
  in_range("SparseViewOptions.tracked_weight", tracked_weight, 0.0, 1.0);
  in_range("SparseViewOptions.smooth_frames", smooth_frames, 0, 100);
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

}  // namespace stillslam
