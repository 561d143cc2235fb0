#include "stillslam/loop/loop_verification.h"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "stillslam/features/descriptor.h"
#include "stillslam/map/keyframe_point_features.h"
#include "stillslam/map/matching_thresholds.h"
#include "stillslam/optimize/pose_optimizer.h"
#include "stillslam/place/direct_index_matcher.h"

namespace stillslam {

namespace {

// A keypoint in its camera frame: from its depth, else from its map point.
std::optional<Eigen::Vector3d> camera_point(const LoopSnapshot& s, const KeyFrameCopy& kf, std::size_t i) {
  const KeyFrame& features = *kf.keyframe;
  if (features.depth(i) > 0) {
    const cv::Point2f& pt = features.keypoint(i).pt;
    return features.setup().camera.unproject(Eigen::Vector2d(pt.x, pt.y), features.depth(i));
  }
  const std::int32_t p = kf.point_index[i];
  if (p < 0) return std::nullopt;
  return kf.T_cam_world * s.points[static_cast<std::size_t>(p)].position;
}

// Best keypoint of `kf` for a map point projected with T_cam_world, or -1.
std::ptrdiff_t match_projection(const KeyFrame& kf, const Eigen::Isometry3d& T_cam_world, const PointCopy& mp,
                                float window) {
  const CameraSetup& setup = kf.setup();
  const Eigen::Vector3d p = T_cam_world * mp.position;
  if (p.z() <= 0) return -1;
  const Eigen::Vector2d uv = setup.camera.project(p);
  if (!setup.camera.in_image(uv)) return -1;
  const Eigen::Vector3d ray = mp.position - T_cam_world.inverse().translation();
  const double distance = ray.norm();
  if (distance < mp.min_distance || distance > mp.max_distance) return -1;
  if (ray.dot(mp.normal) < 0.5 * distance) return -1;
  const int level = predict_scale_level(mp.level_reference_distance, distance, setup.pyramid);
  const float radius = window * setup.pyramid.scale[static_cast<std::size_t>(level)];
  int best_distance = kDescriptorDistanceLow + 1;
  std::ptrdiff_t best = -1;
  for (std::size_t j :
       kf.features_in_area(static_cast<float>(uv.x()), static_cast<float>(uv.y()), radius, level - 1, level + 1)) {
    const int d = descriptor_distance(mp.descriptor.data(), kf.descriptor(j));
    if (d < best_distance) {
      best_distance = d;
      best = static_cast<std::ptrdiff_t>(j);
    }
  }
  return best;
}

}  // namespace

std::optional<LoopDetection> verify_candidate(const LoopSnapshot& s, const LoopCandidateCopy& candidate,
                                              const LoopDetectorOptions& options) {
  if (!candidate.words || !s.query_words) return std::nullopt;
  const KeyFrame& query = *s.query.keyframe;
  const KeyFrame& loop = *candidate.keyframe.keyframe;
  const KeyframePointFeatures q = keyframe_point_features(query, s.query.point_index, s.query_words->features);
  const KeyframePointFeatures c = keyframe_point_features(loop, candidate.keyframe.point_index, candidate.words->features);
  if (q.slot.empty() || c.slot.empty()) return std::nullopt;
  const std::vector<cv::DMatch> matches =
      match_by_direct_index(q.descriptors, q.groups, c.descriptors, c.groups, options.bow_matching);
  if (static_cast<int>(matches.size()) < options.min_bow_matches) {
    spdlog::debug("loop candidate {} for {}: {} BoW matches", loop.id(), query.id(), matches.size());
    return std::nullopt;
  }

  // SE3 between the two cameras from their own measurements.
  const Eigen::Isometry3d T_world_loop = candidate.keyframe.T_cam_world.inverse();
  std::vector<Eigen::Vector3d> src, dst;
  std::vector<std::size_t> src_index;
  std::vector<std::int32_t> dst_point;
  for (const cv::DMatch& m : matches) {
    const std::size_t qi = q.slot[static_cast<std::size_t>(m.queryIdx)];
    const std::size_t ci = c.slot[static_cast<std::size_t>(m.trainIdx)];
    const auto pq = camera_point(s, s.query, qi);
    const auto pc = camera_point(s, candidate.keyframe, ci);
    if (!pq || !pc) continue;
    src.push_back(*pq);
    dst.push_back(T_world_loop * *pc);
    src_index.push_back(qi);
    dst_point.push_back(candidate.keyframe.point_index[ci]);
  }
  if (static_cast<int>(src.size()) < options.min_bow_matches) return std::nullopt;
  const AlignmentResult a = align_ransac(src, dst, options.alignment);
  if (!a.success) {
    spdlog::debug("loop candidate {} for {}: no SE3 from {} 3D-3D matches", loop.id(), query.id(), src.size());
    return std::nullopt;
  }
  Eigen::Isometry3d T_cam_world = a.S_dst_src.rigid().inverse();

  // Guided search of the loop keyframe's local map with the corrected pose
  // (point indices into the snapshot until the end).
  std::vector<std::int32_t> matched_point(query.size(), -1);
  std::vector<bool> matched(s.points.size(), false);
  for (std::size_t k = 0; k < src.size(); ++k) {
    if (a.inlier[k]) matched_point[src_index[k]] = dst_point[k];
  }
  for (std::int32_t p : matched_point) {
    if (p >= 0) matched[static_cast<std::size_t>(p)] = true;
  }
  for (std::int32_t p : candidate.loop_points) {
    if (matched[static_cast<std::size_t>(p)]) continue;
    const std::ptrdiff_t j =
        match_projection(query, T_cam_world, s.points[static_cast<std::size_t>(p)], options.projection_window);
    if (j < 0 || matched_point[static_cast<std::size_t>(j)] >= 0) continue;
    matched_point[static_cast<std::size_t>(j)] = p;
    matched[static_cast<std::size_t>(p)] = true;
  }

  // Refine the pose on all matches; keep the inliers.
  const CameraSetup& setup = query.setup();
  std::vector<PoseObservation> observations;
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < query.size(); ++i) {
    if (matched_point[i] < 0) continue;
    const cv::KeyPoint& kp = query.keypoint(i);
    PoseObservation o;
    o.point_world = s.points[static_cast<std::size_t>(matched_point[i])].position;
    o.pixel = Eigen::Vector2d(kp.pt.x, kp.pt.y);
    o.u_right = query.u_right(i);
    o.inv_sigma2 = setup.pyramid.inv_sigma2[static_cast<std::size_t>(kp.octave)];
    observations.push_back(o);
    index.push_back(i);
  }
  const PoseOptimizationResult r = static_cast<int>(observations.size()) < options.min_inliers
                                       ? PoseOptimizationResult{}
                                       : optimize_pose(setup.camera, T_cam_world, observations);
  spdlog::debug("loop candidate {} for {}: {} BoW matches, {} 3D-3D ({} RANSAC inliers), {} after guided search, {} "
                "inliers", loop.id(), query.id(), matches.size(), src.size(),
                std::count(a.inlier.begin(), a.inlier.end(), true), observations.size(), r.num_inliers);
  if (static_cast<int>(observations.size()) < options.min_inliers || r.num_inliers < options.min_inliers) {
    return std::nullopt;
  }
  LoopDetection d;
  d.query = s.query.keyframe;
  d.loop = candidate.keyframe.keyframe;
  d.matched_points.assign(query.size(), nullptr);
  for (std::size_t k = 0; k < index.size(); ++k) {
    if (r.inlier[k]) d.matched_points[index[k]] = s.points[static_cast<std::size_t>(matched_point[index[k]])].point;
  }
  d.loop_points.reserve(candidate.loop_points.size());
  for (std::int32_t p : candidate.loop_points) d.loop_points.push_back(s.points[static_cast<std::size_t>(p)].point);
  d.inliers = r.num_inliers;
  d.T_world_query_corrected = r.T_cam_world.inverse();
  return d;
}

int count_confirmations(const LoopSnapshot& s, const LoopCandidateCopy& candidate, const LoopDetection& detection,
                        const LoopDetectorOptions& options) {
  // World correction of the drifted side: T_world_new = C * T_world_old.
  const Eigen::Isometry3d C = detection.T_world_query_corrected * s.query.T_cam_world;
  int confirmed = 0;
  for (const KeyFrameCopy& k : s.neighbours) {
    if (k.keyframe == candidate.keyframe.keyframe) continue;
    const Eigen::Isometry3d T_cam_world = k.T_cam_world * C.inverse();
    std::vector<bool> taken(k.keyframe->size(), false);
    int matches = 0;
    for (std::int32_t p : candidate.loop_points) {
      const std::ptrdiff_t j =
          match_projection(*k.keyframe, T_cam_world, s.points[static_cast<std::size_t>(p)], options.projection_window);
      if (j < 0 || taken[static_cast<std::size_t>(j)]) continue;
      taken[static_cast<std::size_t>(j)] = true;
      ++matches;
    }
    if (matches >= options.min_confirmation_matches) ++confirmed;
  }
  return confirmed;
}

}  // namespace stillslam
