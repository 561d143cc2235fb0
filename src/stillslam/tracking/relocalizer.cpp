#include "stillslam/tracking/relocalizer.h"

#include <algorithm>
#include <array>
#include <unordered_set>

#include "stillslam/core/option_check.h"
#include "stillslam/map/projection_search.h"
#include "stillslam/map/keyframe_point_features.h"
#include "stillslam/place/direct_index_matcher.h"
#include "stillslam/tracking/pose_refinement.h"

namespace stillslam {

namespace {

constexpr int kCells = 4;  // verification grid: kCells x kCells image cells

// The candidate's local map: its points and those of its best covisibles.
std::vector<MapPointPtr> local_map_points(const KeyFrame& kf) {
  std::unordered_set<const MapPoint*> seen;
  std::vector<MapPointPtr> out;
  auto add_points = [&](const KeyFrame& k) {
    for (const MapPointPtr& mp : k.map_points()) {
      if (mp && !mp->is_bad() && !mp->is_provisional() && seen.insert(mp.get()).second) out.push_back(mp);
    }
  };
  add_points(kf);
  for (KeyFrame* n : kf.best_covisibles(10)) {
    if (!n->is_bad()) add_points(*n);
  }
  return out;
}

// Projects the candidate's local map into the posed frame and matches the
// points not matched yet.
int search_local_map(Frame& frame, const KeyFrame& kf, float window) {
  std::unordered_set<const MapPoint*> known;
  for (const MapPointPtr& mp : frame.map_points()) {
    if (mp) known.insert(mp.get());
  }
  std::vector<ProjectedPoint> projected;
  for (const MapPointPtr& mp : local_map_points(kf)) {
    if (known.count(mp.get())) continue;
    if (auto p = project_in_frustum(frame, mp)) projected.push_back(*p);
  }
  return search_by_projection(frame, projected, window / 2.5f, 0.9f);
}

}  // namespace

RelocalizationResult Relocalizer::relocalize(Frame& frame, const FeatureVector& frame_features,
                                             const std::vector<RelocalizationCandidate>& candidates) const {
  RelocalizationResult best;
  for (const RelocalizationCandidate& candidate : candidates) {
    if (!candidate.keyframe || candidate.keyframe->is_bad()) continue;
    // Each attempt works on a copy: a rejected pose never reaches the frame.
    Frame attempt = frame;
    RelocalizationResult r = try_candidate(attempt, frame_features, candidate);
    r.candidates_tried = best.candidates_tried + 1;
    const int rejected = best.rejected_by_verification + (r.checked_points > 0 && !r.success ? 1 : 0);
    r.rejected_by_verification = rejected;
    if (r.success) {
      frame = std::move(attempt);
      return r;
    }
    if (r.inliers > best.inliers) best = r;
    best.candidates_tried = r.candidates_tried;
    best.rejected_by_verification = rejected;
  }
  frame.clear_map_points();
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
  if (!verify(frame, kf, result)) {
    frame.clear_map_points();
    return result;
  }
  result.success = true;
  result.T_cam_world = frame.T_cam_world();
  frame.set_reference_keyframe(candidate.keyframe);
  return result;
}

bool Relocalizer::verify(Frame& frame, const KeyFrame& kf, RelocalizationResult& result) const {
  // One more guided search with the optimized pose, so that every predicted
  // point had its chance (the BoW matches alone cover a fraction of them).
  search_local_map(frame, kf, options_.fine_window);
  refine_pose(frame);
  result.inliers = discard_outliers(frame);
  if (result.inliers < options_.min_inliers) return false;
  if (options_.min_found_ratio <= 0 && options_.min_supported_cells <= 0) return true;

  std::unordered_set<const MapPoint*> matched;
  for (const MapPointPtr& mp : frame.map_points()) {
    if (mp) matched.insert(mp.get());
  }
  const ScalePyramid& pyramid = frame.setup().pyramid;
  const PinholeCamera& camera = frame.setup().camera;
  std::array<int, kCells * kCells> cell_checked{}, cell_found{};
  int checked = 0, found = 0;
  for (const MapPointPtr& mp : local_map_points(kf)) {
    const std::optional<ProjectedPoint> p = project_in_frustum(frame, mp);
    if (!p) continue;
    const auto x = static_cast<float>(p->pixel.x()), y = static_cast<float>(p->pixel.y());
    const bool is_found = matched.count(mp.get()) > 0;
    if (!is_found) {
      const float r = options_.check_radius * pyramid.scale[static_cast<std::size_t>(p->level)];
      if (frame.features_in_area(x, y, r, p->level - 1, p->level + 1).empty()) continue;
    }
    const int cx = std::clamp(static_cast<int>(x * kCells / camera.width()), 0, kCells - 1);
    const int cy = std::clamp(static_cast<int>(y * kCells / camera.height()), 0, kCells - 1);
    ++checked;
    ++cell_checked[static_cast<std::size_t>(cy * kCells + cx)];
    if (is_found) {
      ++found;
      ++cell_found[static_cast<std::size_t>(cy * kCells + cx)];
    }
  }
  int judged_cells = 0, supported_cells = 0;
  for (std::size_t c = 0; c < cell_checked.size(); ++c) {
    if (cell_checked[c] < options_.min_cell_predictions) continue;
    ++judged_cells;
    if (cell_found[c] >= std::max(2.0, options_.min_cell_found_ratio * cell_checked[c])) ++supported_cells;
  }
  result.checked_points = checked;
  result.found_points = found;
  result.judged_cells = judged_cells;
  result.supported_cells = supported_cells;
  if (checked >= options_.min_checked_points && found < options_.min_found_ratio * checked) return false;
  if (judged_cells >= options_.min_judged_cells && supported_cells < options_.min_supported_cells * judged_cells) {
    return false;
  }
  return true;
}

void RelocalizerOptions::check() const {
  using namespace option_check;
  at_least("RelocalizerOptions.min_bow_matches", min_bow_matches, 1);
  at_least("RelocalizerOptions.min_inliers", min_inliers, 1);
  at_least("RelocalizerOptions.min_ransac_inliers", min_ransac_inliers, 1);
  in_range("RelocalizerOptions.min_depth_fraction", min_depth_fraction, 0, 1);
  above("RelocalizerOptions.coarse_window", coarse_window, 0);
  above("RelocalizerOptions.fine_window", fine_window, 0);
  in_range("RelocalizerOptions.min_found_ratio", min_found_ratio, 0, 1);
  at_least("RelocalizerOptions.min_checked_points", min_checked_points, 0);
  in_range("RelocalizerOptions.min_supported_cells", min_supported_cells, 0, 1);
  at_least("RelocalizerOptions.min_judged_cells", min_judged_cells, 0);
  at_least("RelocalizerOptions.min_cell_predictions", min_cell_predictions, 0);
  in_range("RelocalizerOptions.min_cell_found_ratio", min_cell_found_ratio, 0, 1);
  above("RelocalizerOptions.check_radius", check_radius, 0);
}

}  // namespace stillslam
