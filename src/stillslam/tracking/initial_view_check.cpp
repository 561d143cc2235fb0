#include "stillslam/tracking/initial_view_check.h"

#include <algorithm>
#include <cmath>

#include "stillslam/core/option_check.h"
#include "stillslam/features/descriptor_matcher.h"
#include "stillslam/features/scale_pyramid.h"
#include "stillslam/geometry/pnp.h"
#include "stillslam/map/matching_thresholds.h"

namespace stillslam {

namespace {

int percent(double share) { return static_cast<int>(std::lround(100 * share)); }

// The mask is looked up at undistorted coordinates: near the border of a
// distorted image a few pixels off, which the mask dilation covers.
bool in_mask(const cv::Mat1b& mask, const Eigen::Vector2d& pixel) {
  const int x = static_cast<int>(std::floor(pixel.x())), y = static_cast<int>(std::floor(pixel.y()));
  return !mask.empty() && x >= 0 && y >= 0 && x < mask.cols && y < mask.rows && mask(y, x) != 0;
}

}  // namespace

InitialViewCheck check_initial_view(const Frame& first, const Frame& next, const InitialViewCheckOptions& options) {
  InitialViewCheck out;
  out.keep.assign(first.size(), true);
  const double masked = std::max(first.masked_fraction(), next.masked_fraction());
  if (masked > options.max_masked_fraction) {
    out.reason = "waiting for two frames at most " + std::to_string(percent(options.max_masked_fraction)) +
                 " % masked (has " + std::to_string(percent(masked)) + " %)";
    return out;
  }

  const PinholeCamera& camera = first.setup().camera;
  std::vector<std::size_t> with_depth;
  cv::Mat query;
  for (std::size_t i = 0; i < first.size(); ++i) {
    if (first.depth(i) <= 0) continue;
    with_depth.push_back(i);
    query.push_back(first.descriptors().row(static_cast<int>(i)));
  }
  DescriptorMatchOptions match_options;
  match_options.max_distance = kDescriptorDistanceLow;
  const std::vector<cv::DMatch> matches =
      query.empty() ? std::vector<cv::DMatch>{} : match_descriptors(query, next.descriptors(), match_options);
  std::vector<Eigen::Vector3d> points;  // in the first camera's frame
  std::vector<Eigen::Vector2d> pixels;
  for (const cv::DMatch& m : matches) {
    const std::size_t i = with_depth[static_cast<std::size_t>(m.queryIdx)];
    const cv::Point2f& p = first.keypoint(i).pt;
    points.push_back(camera.unproject(Eigen::Vector2d(p.x, p.y), first.depth(i)));
    const cv::Point2f& q = next.keypoint(static_cast<std::size_t>(m.trainIdx)).pt;
    pixels.emplace_back(q.x, q.y);
  }
  out.matches = static_cast<int>(matches.size());
  if (out.matches < options.min_matches) {
    out.reason = "first keyframe check: " + std::to_string(out.matches) + " matches with the next frame";
    return out;
  }
  const bool unmasked = first.dynamic_mask().empty() && next.dynamic_mask().empty();
  PnpRansacOptions pnp;
  pnp.max_reprojection_error_px =
      unmasked ? options.max_reprojection_error_unmasked_px : options.max_reprojection_error_px;
  const PnpResult motion = solve_pnp_ransac(camera, points, pixels, pnp);
  out.moving = motion.success ? out.matches - motion.num_inliers : out.matches;
  const double max_moving_share = unmasked ? options.max_moving_share_unmasked : options.max_moving_share;
  if (out.moving > max_moving_share * out.matches) {
    out.reason = "first keyframe check: " + std::to_string(out.moving) + " of " + std::to_string(out.matches) +
                 " matches move against the camera (a dynamic object the mask missed?)";
    return out;
  }

  // Without masks a match confirms its point only within the level-0 bound
  // (the RANSAC's), but it finds the point moving only beyond a bound scaled
  // by moving_factor_unmasked and by the coarser of its two keypoints'
  // pyramid levels (as the pose stages weight errors by sigma^2): a static
  // point detected at a coarse level is a few pixels off in one frame, not
  // moving.
  std::vector<bool> agrees = motion.inlier;
  if (unmasked && motion.success) {
    const ScalePyramid& pyramid = first.setup().pyramid;
    for (std::size_t k = 0; k < matches.size(); ++k) {
      const std::size_t i = with_depth[static_cast<std::size_t>(matches[k].queryIdx)];
      const int level = std::max(first.keypoint(i).octave,
                                 next.keypoint(static_cast<std::size_t>(matches[k].trainIdx)).octave);
      const double bound = options.max_reprojection_error_unmasked_px * options.moving_factor_unmasked *
                           pyramid.scale[static_cast<std::size_t>(std::clamp(level, 0, pyramid.n_levels - 1))];
      const Eigen::Vector3d in_next = motion.T_cam_world * points[k];
      agrees[k] = in_next.z() > 0 && (camera.project(in_next) - pixels[k]).norm() <= bound;
    }
  }
  out.confirmed.assign(first.size(), false);
  out.matched.assign(first.size(), false);
  out.next_keypoint.assign(first.size(), -1);
  for (std::size_t k = 0; k < matches.size(); ++k) {
    const std::size_t i = with_depth[static_cast<std::size_t>(matches[k].queryIdx)];
    out.matched[i] = true;
    out.keep[i] = agrees[k];
    out.confirmed[i] = motion.inlier[k];
    if (motion.inlier[k]) out.next_keypoint[i] = matches[k].trainIdx;
  }
  for (const std::size_t i : with_depth) {
    const cv::Point2f& p = first.keypoint(i).pt;
    const Eigen::Vector3d in_next = motion.T_cam_world * camera.unproject(Eigen::Vector2d(p.x, p.y), first.depth(i));
    if (in_next.z() > 0 && in_mask(next.dynamic_mask(), camera.project(in_next))) out.keep[i] = false;
  }
  out.T_next_first = motion.T_cam_world;
  out.accepted = true;
  return out;
}

void InitialViewCheckOptions::check() const {
  using namespace option_check;
  in_range("InitialViewCheckOptions.max_masked_fraction", max_masked_fraction, 0, 1);
  in_range("InitialViewCheckOptions.max_moving_share", max_moving_share, 0, 1);
  in_range("InitialViewCheckOptions.max_moving_share_unmasked", max_moving_share_unmasked, 0, 1);
  at_least("InitialViewCheckOptions.min_matches", min_matches, 1);
  above("InitialViewCheckOptions.max_reprojection_error_px", max_reprojection_error_px, 0);
  above("InitialViewCheckOptions.max_reprojection_error_unmasked_px", max_reprojection_error_unmasked_px, 0);
  in_range("InitialViewCheckOptions.moving_factor_unmasked", moving_factor_unmasked, 1, 100);
}

}  // namespace stillslam
