#include "stillslam/tracking/instance_motion_check.h"

#include <algorithm>
#include <cmath>

#include "stillslam/core/error.h"
#include "stillslam/core/option_check.h"
#include "stillslam/features/descriptor.h"
#include "stillslam/features/descriptor_matcher.h"
#include "stillslam/tracking/motion_residual.h"

namespace stillslam {

namespace {

// match_descriptors(cur, prev) with each pair offered only when prev's
// predicted pixel in cur lies within `window` px of cur's on both axes: the
// same ratio test and cross check, over the pairs of a grid of cur's features.
std::vector<cv::DMatch> match_in_window(const PinholeCamera& camera, const Eigen::Isometry3d& T_cur_prev,
                                        const MotionCheckFrame& cur, const MotionCheckFrame& prev, double window,
                                        const DescriptorMatchOptions& options) {
  if (cur.pixels.empty() || prev.pixels.empty()) return {};
  double max_u = 0, max_v = 0;
  for (const Eigen::Vector2d& p : cur.pixels) {
    max_u = std::max(max_u, p.x());
    max_v = std::max(max_v, p.y());
  }
  const int cols = static_cast<int>(max_u / window) + 1, rows = static_cast<int>(max_v / window) + 1;
  std::vector<std::vector<int>> grid(static_cast<std::size_t>(cols * rows));
  const auto cell = [window](double x) { return static_cast<int>(std::floor(x / window)); };
  for (std::size_t c = 0; c < cur.pixels.size(); ++c) {
    const int cu = std::max(0, cell(cur.pixels[c].x())), cv_ = std::max(0, cell(cur.pixels[c].y()));
    grid[static_cast<std::size_t>(cv_ * cols + cu)].push_back(static_cast<int>(c));
  }
  MatchCandidates candidates(cur.pixels.size(), prev.pixels.size());
  for (std::size_t p = 0; p < prev.pixels.size(); ++p) {
    const Eigen::Vector3d ray = prev.depth[p] > 0 ? T_cur_prev * camera.unproject(prev.pixels[p], prev.depth[p])
                                                  : T_cur_prev.linear() * camera.unproject(prev.pixels[p], 1.0);
    if (ray.z() <= 1e-6) continue;
    const Eigen::Vector2d q = camera.project(ray);
    const int u0 = std::max(0, cell(q.x() - window)), u1 = std::min(cols - 1, cell(q.x() + window));
    const int v0 = std::max(0, cell(q.y() - window)), v1 = std::min(rows - 1, cell(q.y() + window));
    const std::uint8_t* b = prev.descriptors.ptr<std::uint8_t>(static_cast<int>(p));
    for (int v = v0; v <= v1; ++v) {
      for (int u = u0; u <= u1; ++u) {
        for (int c : grid[static_cast<std::size_t>(v * cols + u)]) {
          const Eigen::Vector2d& x = cur.pixels[static_cast<std::size_t>(c)];
          if (std::abs(x.x() - q.x()) > window || std::abs(x.y() - q.y()) > window) continue;
          candidates.offer(c, static_cast<int>(p), descriptor_distance(cur.descriptors.ptr<std::uint8_t>(c), b));
        }
      }
    }
  }
  return candidates.matches(options);
}

}  // namespace

void InstanceMotionCheckOptions::check() const {
  using namespace option_check;
  at_least("InstanceMotionCheckOptions.span", span, 1);
  in_range("InstanceMotionCheckOptions.max_hamming", max_hamming, 0, 256);
  in_range("InstanceMotionCheckOptions.ratio", ratio, 0.01, 1);
  in_range("InstanceMotionCheckOptions.window_px", window_px, 0, 10000);
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

void InstanceMotionCheck::check_lengths(const MotionCheckFrame& frame) {
  const std::size_t n = frame.pixels.size();
  if (frame.depth.size() != n || frame.instance.size() != n || static_cast<std::size_t>(frame.descriptors.rows) != n) {
    throw Error("InstanceMotionCheck: pixels, depth, instance ids and descriptors of a frame must have one entry per feature");
  }
}

void InstanceMotionCheck::compare(const MotionCheckFrame& prev, const MotionCheckFrame& cur,
                                  MotionCheckResult& result) const {
  result.compared = true;
  const Eigen::Isometry3d T_cur_prev = cur.T_cam_world * prev.T_cam_world.inverse();
  DescriptorMatchOptions match;
  match.max_distance = options_.max_hamming;
  match.ratio = options_.ratio;
  const std::vector<cv::DMatch> matches =
      options_.window_px > 0 ? match_in_window(camera_, T_cur_prev, cur, prev, options_.window_px, match)
                             : match_descriptors(cur.descriptors, prev.descriptors, match);
  for (const cv::DMatch& m : matches) {
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
}

namespace {

std::vector<InstanceResiduals> instance_residuals(const MotionCheckFrame& cur, const MotionCheckResult& result) {
  std::vector<InstanceResiduals> instances;
  for (const auto& [id, residuals] : result.residuals) {
    const auto category = cur.categories.find(id);
    instances.push_back({static_cast<int>(id), category != cur.categories.end() ? category->second : "", residuals,
                         cur.objects.count(id) > 0});
  }
  return instances;
}

}  // namespace

MotionCheckResult InstanceMotionCheck::add(MotionCheckFrame frame) {
  check_lengths(frame);
  frames_.push_back(std::move(frame));
  if (static_cast<int>(frames_.size()) > options_.span + 1) frames_.pop_front();
  MotionCheckResult result;
  if (static_cast<int>(frames_.size()) < options_.span + 1) return result;
  compare(frames_.front(), frames_.back(), result);
  result.instances = evidence_.update(result.background_residuals, instance_residuals(frames_.back(), result));
  result.background_matches = static_cast<int>(result.background_residuals.size());
  result.background_median_px = evidence_.background_median();
  return result;
}

MotionCheckResult InstanceMotionCheck::peek(const MotionCheckFrame& frame) const {
  check_lengths(frame);
  MotionCheckResult result;
  if (static_cast<int>(frames_.size()) < options_.span) return result;
  compare(frames_[frames_.size() - static_cast<std::size_t>(options_.span)], frame, result);
  result.instances = evidence_.peek(result.background_residuals, instance_residuals(frame, result));
  result.background_matches = static_cast<int>(result.background_residuals.size());
  std::vector<double> bg = result.background_residuals;
  result.background_median_px = median_of(bg);
  return result;
}

}  // namespace stillslam
