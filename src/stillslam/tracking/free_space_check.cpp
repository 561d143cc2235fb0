#include "stillslam/tracking/free_space_check.h"

#include <algorithm>
#include <cmath>

#include "stillslam/core/check.h"
#include "stillslam/core/option_check.h"

namespace stillslam {

void FreeSpaceOptions::check() const {
  using namespace option_check;
  in_range("FreeSpaceOptions.step_px", step_px, 1, 64);
  at_least("FreeSpaceOptions.min_gap_m", min_gap_m, 0);
  at_least("FreeSpaceOptions.gap_share_of_depth", gap_share_of_depth, 0);
}

std::map<std::uint32_t, FreeSpaceCount> count_seen_through(const PinholeCamera& camera, const cv::Mat& depth,
                                                           const cv::Mat1i& labels,
                                                           const std::set<std::uint32_t>& ids,
                                                           const Eigen::Isometry3d& T_earlier_current,
                                                           const cv::Mat& earlier_depth,
                                                           const FreeSpaceOptions& options,
                                                           const cv::Mat1b& earlier_occluders) {
  STILLSLAM_CHECK(depth.type() == CV_32F && earlier_depth.type() == CV_32F, "depth images must be CV_32F");
  STILLSLAM_CHECK(depth.size() == labels.size() && earlier_depth.size() == labels.size(), "images of one size");
  STILLSLAM_CHECK(earlier_occluders.empty() || earlier_occluders.size() == labels.size(), "images of one size");
  std::map<std::uint32_t, FreeSpaceCount> out;
  for (std::uint32_t id : ids) out[id];
  const int step = std::max(1, options.step_px);
  for (int v = step / 2; v < labels.rows; v += step) {
    const int* label_row = labels.ptr<int>(v);
    const float* depth_row = depth.ptr<float>(v);
    for (int u = step / 2; u < labels.cols; u += step) {
      const auto it = out.find(static_cast<std::uint32_t>(label_row[u]));
      if (it == out.end()) continue;
      const float z = depth_row[u];
      if (!(z > 0)) continue;
      const Eigen::Vector3d p = T_earlier_current * camera.unproject(Eigen::Vector2d(u, v), z);
      if (p.z() <= 1e-6) continue;
      const Eigen::Vector2d q = camera.project(p);
      const int qu = static_cast<int>(std::lround(q.x())), qv = static_cast<int>(std::lround(q.y()));
      if (qu < 0 || qv < 0 || qu >= earlier_depth.cols || qv >= earlier_depth.rows) continue;
      const float seen = earlier_depth.at<float>(qv, qu);
      if (!(seen > 0)) continue;
      if (!earlier_occluders.empty() && earlier_occluders(qv, qu)) continue;
      ++it->second.samples;
      const double gap = std::max(options.min_gap_m, options.gap_share_of_depth * p.z());
      it->second.seen_through += seen > p.z() + gap;
      it->second.seen_nearer += options.count_nearer && seen < p.z() - gap;
    }
  }
  return out;
}

}  // namespace stillslam
