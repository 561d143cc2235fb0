#include "stillslam/tracking/instance_motion_check.h"

#include "stillslam/core/error.h"
#include "stillslam/core/option_check.h"
#include "stillslam/features/descriptor_matcher.h"
#include "stillslam/tracking/motion_residual.h"

namespace stillslam {

void InstanceMotionCheckOptions::check() const {
  using namespace option_check;
  at_least("InstanceMotionCheckOptions.span", span, 1);
  in_range("InstanceMotionCheckOptions.max_hamming", max_hamming, 0, 256);
  in_range("InstanceMotionCheckOptions.ratio", ratio, 0.01, 1);
  evidence.check();
}

InstanceMotionCheck::InstanceMotionCheck(const PinholeCamera& camera, InstanceMotionCheckOptions options)
    : camera_(camera), options_(std::move(options)), evidence_(options_.evidence) {
  options_.check();
}

void InstanceMotionCheck::reset() {
  frames_.clear();
  evidence_ = MotionEvidence(options_.evidence);
}

void InstanceMotionCheck::relabel(std::uint32_t from, std::uint32_t to) {
  evidence_.forget(static_cast<int>(from));
  for (MotionCheckFrame& f : frames_) {
    for (std::uint32_t& id : f.instance) {
      if (id == from) id = to;
    }
    if (const auto it = f.categories.find(from); it != f.categories.end()) {
      f.categories[to] = it->second;
      f.categories.erase(from);
    }
    if (f.objects.erase(from)) f.objects.insert(to);
  }
}

MotionCheckResult InstanceMotionCheck::add(MotionCheckFrame frame) {
  const std::size_t n = frame.pixels.size();
  if (frame.depth.size() != n || frame.instance.size() != n || static_cast<std::size_t>(frame.descriptors.rows) != n) {
    throw Error("InstanceMotionCheck: pixels, depth, instance ids and descriptors of a frame must have one entry per feature");
  }
  frames_.push_back(std::move(frame));
  if (static_cast<int>(frames_.size()) > options_.span + 1) frames_.pop_front();
  MotionCheckResult result;
  if (static_cast<int>(frames_.size()) < options_.span + 1) return result;
  result.compared = true;
  const MotionCheckFrame& prev = frames_.front();
  const MotionCheckFrame& cur = frames_.back();
  const Eigen::Isometry3d T_cur_prev = cur.T_cam_world * prev.T_cam_world.inverse();
  DescriptorMatchOptions match;
  match.max_distance = options_.max_hamming;
  match.ratio = options_.ratio;
  for (const cv::DMatch& m : match_descriptors(cur.descriptors, prev.descriptors, match)) {
    const std::size_t c = static_cast<std::size_t>(m.queryIdx), p = static_cast<std::size_t>(m.trainIdx);
    // Across an instance border, or from an instance to the background: not
    // comparable. From the background to an instance is: an object nobody
    // segmented before (a box at rest) that is now an instance of its own.
    if (cur.instance[c] != prev.instance[p] && prev.instance[p] != 0) continue;
    const double r = prev.depth[p] > 0
                         ? reprojection_residual(camera_, T_cur_prev, prev.pixels[p], prev.depth[p], cur.pixels[c])
                         : epipolar_residual(camera_, T_cur_prev, prev.pixels[p], cur.pixels[c]);
    (cur.instance[c] == 0 ? result.background_residuals : result.residuals[cur.instance[c]]).push_back(r);
  }
  std::vector<InstanceResiduals> instances;
  for (const auto& [id, residuals] : result.residuals) {
    const auto category = cur.categories.find(id);
    instances.push_back({static_cast<int>(id), category != cur.categories.end() ? category->second : "", residuals,
                         cur.objects.count(id) > 0});
  }
  result.instances = evidence_.update(result.background_residuals, instances);
  result.background_matches = static_cast<int>(result.background_residuals.size());
  result.background_median_px = evidence_.background_median();
  return result;
}

}  // namespace stillslam
