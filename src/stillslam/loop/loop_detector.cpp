#include "stillslam/loop/loop_detector.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <map>
#include <unordered_map>
#include <unordered_set>

#include "stillslam/core/option_check.h"
#include "stillslam/features/descriptor.h"
#include "stillslam/map/matching_thresholds.h"
#include "stillslam/optimize/pose_optimizer.h"
#include "stillslam/map/keyframe_point_features.h"
#include "stillslam/place/direct_index_matcher.h"

namespace stillslam {

namespace {

// A keypoint in its camera frame: from its depth, else from its map point.
std::optional<Eigen::Vector3d> camera_point(const KeyFrame& kf, std::size_t i) {
  if (kf.depth(i) > 0) {
    const cv::Point2f& pt = kf.keypoint(i).pt;
    return kf.setup().camera.unproject(Eigen::Vector2d(pt.x, pt.y), kf.depth(i));
  }
  const MapPointPtr& mp = kf.map_point(i);
  if (!mp || mp->is_bad()) return std::nullopt;
  return kf.T_cam_world() * mp->position();
}

// Best keypoint of `kf` for a map point projected with T_cam_world, or -1.
std::ptrdiff_t match_projection(const KeyFrame& kf, const Eigen::Isometry3d& T_cam_world, const MapPoint& mp,
                                float window) {
  const CameraSetup& setup = kf.setup();
  const Eigen::Vector3d p = T_cam_world * mp.position();
  if (p.z() <= 0) return -1;
  const Eigen::Vector2d uv = setup.camera.project(p);
  if (!setup.camera.in_image(uv)) return -1;
  const Eigen::Vector3d ray = mp.position() - T_cam_world.inverse().translation();
  const double distance = ray.norm();
  if (distance < mp.min_distance() || distance > mp.max_distance()) return -1;
  if (ray.dot(mp.normal()) < 0.5 * distance) return -1;
  const int level = mp.predict_level(distance, setup.pyramid);
  const float radius = window * setup.pyramid.scale[static_cast<std::size_t>(level)];
  int best_distance = kDescriptorDistanceLow + 1;
  std::ptrdiff_t best = -1;
  for (std::size_t j :
       kf.features_in_area(static_cast<float>(uv.x()), static_cast<float>(uv.y()), radius, level - 1, level + 1)) {
    const int d = descriptor_distance(mp.descriptor(), kf.descriptor(j));
    if (d < best_distance) {
      best_distance = d;
      best = static_cast<std::ptrdiff_t>(j);
    }
  }
  return best;
}

}  // namespace

LoopDetector::LoopDetector(const PlaceRecognizer& recognizer, LoopDetectorOptions options)
    : recognizer_(recognizer), options_(options) {
  options_.check();
}

void LoopDetector::loop_closed(std::uint64_t query_id) {
  last_loop_id_ = query_id;
  groups_.clear();
  candidate_counts_.clear();
}

std::vector<KeyFramePtr> LoopDetector::candidates(const Map& map, const KeyFrame& query) const {
  std::vector<KeyframeId> covisible;
  for (KeyFrame* k : query.covisibles()) covisible.push_back(k->id());
  const std::vector<PlaceCandidate> found = recognizer_.loop_candidates(query, covisible, 0);
  std::unordered_map<KeyframeId, double> score;
  for (const auto& c : found) score.emplace(c.id, c.score);

  // Accumulate over each candidate's covisible group; the group's best-scoring
  // member represents it.
  struct Group {
    double accumulated = 0;
    KeyFramePtr best;
    double best_score = -1;
  };
  std::vector<Group> groups;
  double best_accumulated = 0;
  for (const auto& c : found) {
    KeyFramePtr kf = map.keyframe(c.id);
    if (!kf || kf->is_bad()) continue;
    Group g;
    g.accumulated = c.score;
    g.best = kf;
    g.best_score = c.score;
    for (KeyFrame* n : kf->best_covisibles(options_.group_size)) {
      const auto it = score.find(n->id());
      if (it == score.end() || n->is_bad()) continue;
      g.accumulated += it->second;
      if (it->second > g.best_score) {
        g.best_score = it->second;
        g.best = n->shared_from_this();
      }
    }
    best_accumulated = std::max(best_accumulated, g.accumulated);
    groups.push_back(std::move(g));
  }
  std::vector<KeyFramePtr> out;
  std::unordered_set<const KeyFrame*> seen;
  for (const Group& g : groups) {
    if (g.accumulated < options_.group_score_ratio * best_accumulated) continue;
    if (seen.insert(g.best.get()).second) out.push_back(g.best);
  }
  return out;
}

std::vector<KeyFramePtr> LoopDetector::consistent_candidates(const std::vector<KeyFramePtr>& candidates) {
  std::vector<ConsistentGroup> current;
  std::vector<KeyFramePtr> enough;
  std::vector<bool> previous_extended(groups_.size(), false);
  candidate_counts_.clear();
  for (const KeyFramePtr& candidate : candidates) {
    int& best_count = candidate_counts_[candidate->id()];
    best_count = 1;
    ConsistentGroup group;
    group.keyframes.insert(candidate->id());
    for (KeyFrame* n : candidate->covisibles()) group.keyframes.insert(n->id());
    bool consistent_for_some = false;
    bool accepted = false;
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      const bool overlaps = std::any_of(group.keyframes.begin(), group.keyframes.end(),
                                        [&](std::uint64_t id) { return groups_[g].keyframes.count(id) > 0; });
      if (!overlaps) continue;
      consistent_for_some = true;
      const int count = groups_[g].count + 1;
      best_count = std::max(best_count, count);
      if (!previous_extended[g]) {
        current.push_back({group.keyframes, count});
        previous_extended[g] = true;
      }
      if (count >= options_.consistency_threshold && !accepted) {
        enough.push_back(candidate);
        accepted = true;
      }
    }
    if (!consistent_for_some) {
      current.push_back({group.keyframes, 1});
      if (options_.consistency_threshold <= 1) enough.push_back(candidate);
    }
  }
  groups_ = std::move(current);
  return enough;
}

std::optional<LoopDetection> LoopDetector::detect(const Map& map, const KeyFrame& query) {
  const auto enough_keyframes = static_cast<std::size_t>(std::max(options_.min_keyframes_between_loops, 0));
  if (map.num_keyframes() <= enough_keyframes ||
      (last_loop_id_ && query.id() < *last_loop_id_ + enough_keyframes)) {
    return std::nullopt;
  }
  const std::vector<KeyFramePtr> found = candidates(map, query);
  if (found.empty()) {
    spdlog::debug("loop detection, keyframe {}: no BoW candidate", query.id());
    groups_.clear();
    return std::nullopt;
  }
  const std::vector<KeyFramePtr> consistent = consistent_candidates(found);
  spdlog::debug("loop detection, keyframe {}: {} BoW candidates (best {}), {} consistent", query.id(), found.size(),
                found.front()->id(), consistent.size());
  if (!consistent.empty()) {
    if (auto d = verify(query, consistent)) return d;
  }
  if (options_.confirmation_neighbours == 0) return std::nullopt;
  std::vector<KeyFramePtr> others;
  for (const KeyFramePtr& c : found) {
    if (std::find(consistent.begin(), consistent.end(), c) == consistent.end()) others.push_back(c);
  }
  return verify_confirmed(query, others);
}

std::optional<LoopDetection> LoopDetector::verify_confirmed(const KeyFrame& query,
                                                            const std::vector<KeyFramePtr>& candidates) const {
  for (const KeyFramePtr& candidate : candidates) {
    std::optional<LoopDetection> d = verify(query, {candidate});
    if (!d) continue;
    const auto count = candidate_counts_.find(candidate->id());
    const int needed = options_.consistency_threshold - (count != candidate_counts_.end() ? count->second : 1);
    d->confirmations = count_confirmations(*d);
    spdlog::debug("loop candidate {} for {}: confirmed by {} covisible keyframes (need {})", candidate->id(),
                  query.id(), d->confirmations, needed);
    if (d->confirmations >= needed) return d;
  }
  return std::nullopt;
}

int LoopDetector::count_confirmations(const LoopDetection& detection) const {
  // World correction of the drifted side: T_world_new = C * T_world_old.
  const Eigen::Isometry3d C = detection.T_world_query_corrected * detection.query->T_cam_world();
  int confirmed = 0;
  for (KeyFrame* k : detection.query->best_covisibles(options_.confirmation_neighbours)) {
    if (k->is_bad() || k == detection.loop.get()) continue;
    const Eigen::Isometry3d T_cam_world = k->T_cam_world() * C.inverse();
    std::vector<bool> taken(k->size(), false);
    int matches = 0;
    for (const MapPointPtr& mp : detection.loop_points) {
      const std::ptrdiff_t j = match_projection(*k, T_cam_world, *mp, options_.projection_window);
      if (j < 0 || taken[static_cast<std::size_t>(j)]) continue;
      taken[static_cast<std::size_t>(j)] = true;
      ++matches;
    }
    if (matches >= options_.min_confirmation_matches) ++confirmed;
  }
  return confirmed;
}

std::optional<LoopDetection> LoopDetector::verify(const KeyFrame& query,
                                                  const std::vector<KeyFramePtr>& candidates) const {
  auto words = recognizer_.description(query.id());
  if (!words) {
    words = std::make_shared<const BowDescription>(recognizer_.describe(PlaceRecognizer::descriptors_of(query)));
  }
  for (const KeyFramePtr& candidate : candidates) {
    if (auto d = verify_one(query, *words, candidate)) return d;
  }
  return std::nullopt;
}

std::optional<LoopDetection> LoopDetector::verify_one(const KeyFrame& query, const BowDescription& query_words,
                                                      const KeyFramePtr& candidate) const {
  if (!candidate || candidate->is_bad()) return std::nullopt;
  const auto candidate_words = recognizer_.description(candidate->id());
  if (!candidate_words) return std::nullopt;
  const KeyframePointFeatures q = keyframe_point_features(query, query_words.features);
  const KeyframePointFeatures c = keyframe_point_features(*candidate, candidate_words->features);
  if (q.slot.empty() || c.slot.empty()) return std::nullopt;
  const std::vector<cv::DMatch> matches =
      match_by_direct_index(q.descriptors, q.groups, c.descriptors, c.groups, options_.bow_matching);
  if (static_cast<int>(matches.size()) < options_.min_bow_matches) {
    spdlog::debug("loop candidate {} for {}: {} BoW matches", candidate->id(), query.id(), matches.size());
    return std::nullopt;
  }

  // SE3 between the two cameras from their own measurements.
  std::vector<Eigen::Vector3d> src, dst;
  std::vector<std::size_t> src_index;
  std::vector<MapPointPtr> dst_point;
  for (const cv::DMatch& m : matches) {
    const std::size_t qi = q.slot[static_cast<std::size_t>(m.queryIdx)];
    const std::size_t ci = c.slot[static_cast<std::size_t>(m.trainIdx)];
    const auto pq = camera_point(query, qi);
    const auto pc = camera_point(*candidate, ci);
    if (!pq || !pc) continue;
    src.push_back(*pq);
    dst.push_back(candidate->T_world_cam() * *pc);
    src_index.push_back(qi);
    dst_point.push_back(candidate->map_point(ci));
  }
  if (static_cast<int>(src.size()) < options_.min_bow_matches) return std::nullopt;
  const AlignmentResult a = align_ransac(src, dst, options_.alignment);
  if (!a.success) {
    spdlog::debug("loop candidate {} for {}: no SE3 from {} 3D-3D matches", candidate->id(), query.id(), src.size());
    return std::nullopt;
  }
  Eigen::Isometry3d T_cam_world = a.S_dst_src.rigid().inverse();

  // Guided search of the loop keyframe's local map with the corrected pose.
  LoopDetection d;
  d.query = std::const_pointer_cast<KeyFrame>(query.shared_from_this());
  d.loop = candidate;
  d.matched_points.assign(query.size(), nullptr);
  for (std::size_t k = 0; k < src.size(); ++k) {
    if (a.inlier[k]) d.matched_points[src_index[k]] = dst_point[k];
  }
  std::unordered_set<const MapPoint*> seen;
  auto collect = [&](const KeyFrame& kf) {
    for (const MapPointPtr& mp : kf.map_points()) {
      if (mp && !mp->is_bad() && seen.insert(mp.get()).second) d.loop_points.push_back(mp);
    }
  };
  collect(*candidate);
  for (KeyFrame* n : candidate->covisibles()) {
    if (!n->is_bad()) collect(*n);
  }
  std::unordered_set<const MapPoint*> matched;
  for (const auto& mp : d.matched_points) {
    if (mp) matched.insert(mp.get());
  }
  for (const MapPointPtr& mp : d.loop_points) {
    if (matched.count(mp.get())) continue;
    const std::ptrdiff_t j = match_projection(query, T_cam_world, *mp, options_.projection_window);
    if (j < 0 || d.matched_points[static_cast<std::size_t>(j)]) continue;
    d.matched_points[static_cast<std::size_t>(j)] = mp;
    matched.insert(mp.get());
  }

  // Refine the pose on all matches; keep the inliers.
  const CameraSetup& setup = query.setup();
  std::vector<PoseObservation> observations;
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < query.size(); ++i) {
    if (!d.matched_points[i]) continue;
    const cv::KeyPoint& kp = query.keypoint(i);
    PoseObservation o;
    o.point_world = d.matched_points[i]->position();
    o.pixel = Eigen::Vector2d(kp.pt.x, kp.pt.y);
    o.u_right = query.u_right(i);
    o.inv_sigma2 = setup.pyramid.inv_sigma2[static_cast<std::size_t>(kp.octave)];
    observations.push_back(o);
    index.push_back(i);
  }
  const PoseOptimizationResult r = static_cast<int>(observations.size()) < options_.min_inliers
                                         ? PoseOptimizationResult{}
                                         : optimize_pose(setup.camera, T_cam_world, observations);
  spdlog::debug("loop candidate {} for {}: {} BoW matches, {} 3D-3D ({} RANSAC inliers), {} after guided search, {} "
                "inliers", candidate->id(), query.id(), matches.size(), src.size(),
                std::count(a.inlier.begin(), a.inlier.end(), true), observations.size(), r.num_inliers);
  if (static_cast<int>(observations.size()) < options_.min_inliers || r.num_inliers < options_.min_inliers) {
    return std::nullopt;
  }
  for (std::size_t k = 0; k < index.size(); ++k) {
    if (!r.inlier[k]) d.matched_points[index[k]] = nullptr;
  }
  d.inliers = r.num_inliers;
  d.T_world_query_corrected = r.T_cam_world.inverse();
  return d;
}

void LoopDetectorOptions::check() const {
  using namespace option_check;
  at_least("LoopDetectorOptions.min_keyframes_between_loops", min_keyframes_between_loops, 0);
  at_least("LoopDetectorOptions.consistency_threshold", consistency_threshold, 1);
  at_least("LoopDetectorOptions.group_size", static_cast<double>(group_size), 1);
  in_range("LoopDetectorOptions.group_score_ratio", group_score_ratio, 0, 1);
  at_least("LoopDetectorOptions.min_bow_matches", min_bow_matches, 1);
  above("LoopDetectorOptions.projection_window", projection_window, 0);
  at_least("LoopDetectorOptions.min_inliers", min_inliers, 1);
  at_least("LoopDetectorOptions.min_confirmation_matches", min_confirmation_matches, 0);
}

}  // namespace stillslam
