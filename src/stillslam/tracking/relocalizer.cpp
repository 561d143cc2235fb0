#include "stillslam/tracking/relocalizer.h"

#include <unordered_set>

#include "stillslam/map/projection_search.h"
#include "stillslam/map/keyframe_point_features.h"
#include "stillslam/place/direct_index_matcher.h"
#include "stillslam/tracking/pose_refinement.h"

namespace stillslam {

namespace {

// Projects the candidate's local map (its points and those of its best
// covisibles) into the posed frame and matches the ones not matched yet.
int search_local_map(Frame& frame, const KeyFrame& kf, float window) {
  std::unordered_set<const MapPoint*> known;
  for (const MapPointPtr& mp : frame.map_points()) {
    if (mp) known.insert(mp.get());
  }
  std::vector<ProjectedPoint> projected;
  auto add_points = [&](const KeyFrame& k) {
    for (const MapPointPtr& mp : k.map_points()) {
      if (!mp || mp->is_bad() || !known.insert(mp.get()).second) continue;
      if (auto p = project_in_frustum(frame, mp)) projected.push_back(*p);
    }
  };
  add_points(kf);
  for (KeyFrame* n : kf.best_covisibles(10)) {
    if (!n->is_bad()) add_points(*n);
  }
  return search_by_projection(frame, projected, window / 2.5f, 0.9f);
}

}  // namespace

RelocalizationResult Relocalizer::relocalize(Frame& frame, const FeatureVector& frame_features,
                                             const std::vector<RelocalizationCandidate>& candidates) const {
  RelocalizationResult best;
  const std::optional<Eigen::Isometry3d> initial_pose =
      frame.has_pose() ? std::optional<Eigen::Isometry3d>(frame.T_cam_world()) : std::nullopt;
  for (const RelocalizationCandidate& candidate : candidates) {
    if (!candidate.keyframe || candidate.keyframe->is_bad()) continue;
    RelocalizationResult r = try_candidate(frame, frame_features, candidate);
    r.candidates_tried = best.candidates_tried + 1;
    if (r.success) return r;
    if (r.inliers > best.inliers) best = r;
    best.candidates_tried = r.candidates_tried;
  }
  frame.clear_map_points();
  if (initial_pose) frame.set_pose(*initial_pose);
  best.success = false;
  return best;
}

RelocalizationResult Relocalizer::try_candidate(Frame& frame, const FeatureVector& frame_features,
                                                const RelocalizationCandidate& candidate) const {
  RelocalizationResult result;
  result.keyframe = candidate.keyframe;
  frame.clear_map_points();
  const KeyFrame& kf = *candidate.keyframe;
  const KeyframePointFeatures pf = keyframe_point_features(kf, candidate.features);
  if (static_cast<int>(pf.slot.size()) < options_.min_bow_matches) return result;
  const std::vector<cv::DMatch> matches =
      match_by_direct_index(frame.descriptors(), frame_features, pf.descriptors, pf.groups, options_.bow_matching);
  if (static_cast<int>(matches.size()) < options_.min_bow_matches) return result;

  // Initial pose from the correspondences.
  std::vector<Eigen::Vector3d> world, cam;
  std::vector<Eigen::Vector2d> pixels;
  std::vector<std::size_t> depth_match;
  for (std::size_t m = 0; m < matches.size(); ++m) {
    const auto i = static_cast<std::size_t>(matches[m].queryIdx);
    const cv::KeyPoint& kp = frame.keypoint(i);
    world.push_back(kf.map_point(pf.slot[static_cast<std::size_t>(matches[m].trainIdx)])->position());
    pixels.emplace_back(kp.pt.x, kp.pt.y);
    if (frame.depth(i) > 0) depth_match.push_back(m);
  }
  std::vector<bool> inlier;
  Eigen::Isometry3d T_cam_world;
  const PinholeCamera& camera = frame.setup().camera;
  const bool use_alignment = static_cast<int>(depth_match.size()) >= options_.min_bow_matches &&
                             static_cast<double>(depth_match.size()) >= options_.min_depth_fraction * matches.size();
  if (use_alignment) {
    std::vector<Eigen::Vector3d> src, dst;
    for (std::size_t m : depth_match) {
      const auto i = static_cast<std::size_t>(matches[m].queryIdx);
      src.push_back(camera.unproject(pixels[m], frame.depth(i)));
      dst.push_back(world[m]);
    }
    const AlignmentResult a = align_ransac(src, dst, options_.alignment);
    if (!a.success || a.num_inliers < options_.min_ransac_inliers) return result;
    T_cam_world = a.S_dst_src.rigid().inverse();
    inlier.assign(matches.size(), false);
    for (std::size_t k = 0; k < depth_match.size(); ++k) inlier[depth_match[k]] = a.inlier[k];
    result.used_alignment = true;
  } else {
    const PnpResult p = solve_pnp_ransac(camera, world, pixels, options_.pnp);
    if (!p.success || p.num_inliers < options_.min_ransac_inliers) return result;
    T_cam_world = p.T_cam_world;
    inlier = p.inlier;
  }

  frame.set_pose(T_cam_world);
  for (std::size_t m = 0; m < matches.size(); ++m) {
    if (!inlier[m]) continue;
    frame.set_map_point(static_cast<std::size_t>(matches[m].queryIdx),
                        kf.map_point(pf.slot[static_cast<std::size_t>(matches[m].trainIdx)]));
  }
  int inliers = refine_pose(frame);
  discard_outliers(frame);
  result.inliers = inliers;
  if (inliers < options_.min_ransac_inliers) {
    frame.clear_map_points();
    return result;
  }
  // Too few: more matches from the candidate's local map, coarse then fine.
  if (inliers < options_.min_inliers) {
    const int added = search_local_map(frame, kf, options_.coarse_window);
    if (inliers + added >= options_.min_inliers) {
      inliers = refine_pose(frame);
      discard_outliers(frame);
      if (inliers > options_.min_inliers / 2 && inliers < options_.min_inliers) {
        search_local_map(frame, kf, options_.fine_window);
        inliers = refine_pose(frame);
        discard_outliers(frame);
      }
    }
  }
  result.inliers = inliers;
  if (inliers < options_.min_inliers) {
    frame.clear_map_points();
    return result;
  }
  result.success = true;
  result.T_cam_world = frame.T_cam_world();
  frame.set_reference_keyframe(candidate.keyframe);
  return result;
}

}  // namespace stillslam
