#include "stillslam/loop/map_merger.h"

#include <set>
#include <unordered_map>
#include <unordered_set>

#include "stillslam/core/option_check.h"
#include "stillslam/loop/global_bundle_adjustment.h"
#include "stillslam/map/fuse.h"
#include "stillslam/optimize/pose_graph.h"

namespace stillslam {

namespace {

using PoseById = std::unordered_map<std::uint64_t, Eigen::Isometry3d>;

// Makes `query` the root of its tree (reversing the path to the old root),
// then hangs it under `loop`.
void reroot_spanning_tree(KeyFrame& query, KeyFrame& loop) {
  std::vector<KeyFrame*> path;
  for (KeyFrame* k = &query; k != nullptr; k = k->parent()) path.push_back(k);
  for (std::size_t i = path.size() - 1; i >= 1; --i) {
    path[i]->erase_child(path[i - 1]);
    path[i]->change_parent(path[i - 1]);
  }
  query.change_parent(&loop);
}

// Step 3. Returns the number of fused or added observations.
int fuse_seam(KeyFrame& query, const LoopDetection& detection, float window) {
  int fused = 0;
  for (std::size_t i = 0; i < detection.matched_points.size(); ++i) {
    const MapPointPtr& target_point = detection.matched_points[i];
    if (!target_point || target_point->is_bad()) continue;
    const MapPointPtr current = query.map_point(i);
    if (current == target_point) continue;
    if (current && !current->is_bad()) {
      current->replace_with(target_point);
    } else {
      target_point->add_observation(&query, i);
      query.set_map_point(i, target_point);
      target_point->compute_distinctive_descriptor();
    }
    ++fused;
  }
  std::vector<KeyFrame*> neighbourhood{&query};
  for (KeyFrame* k : query.covisibles()) {
    if (!k->is_bad()) neighbourhood.push_back(k);
  }
  std::vector<MapPointPtr> target_points;
  for (const MapPointPtr& mp : detection.loop_points) {
    if (!mp->is_bad()) target_points.push_back(mp);
  }
  for (KeyFrame* k : neighbourhood) fused += fuse(*k, target_points, window);
  for (KeyFrame* k : neighbourhood) k->update_connections();
  return fused;
}

// Step 4: the query's source-side neighbourhood is free, everything else fixed.
void welding_bundle_adjustment(KeyFrame& query, const std::unordered_set<const KeyFrame*>& source,
                               const BundleAdjustmentOptions& options, MapMergeStats& stats,
                               std::unordered_set<const KeyFrame*>& free_keyframes,
                               std::unordered_set<const MapPoint*>& adjusted_points) {
  std::vector<KeyFrame*> keyframes;
  std::vector<BaKeyframe> ba_keyframes;
  std::unordered_map<const KeyFrame*, std::size_t> kf_index;
  auto add_keyframe = [&](KeyFrame* k, bool fixed) {
    if (!kf_index.emplace(k, keyframes.size()).second) return;
    keyframes.push_back(k);
    ba_keyframes.push_back({k->id(), k->T_cam_world(), fixed});
  };
  add_keyframe(&query, false);
  for (KeyFrame* k : query.covisibles()) {
    if (!k->is_bad()) add_keyframe(k, source.count(k) == 0);
  }
  std::vector<MapPointPtr> points;
  std::vector<BaPoint> ba_points;
  std::unordered_map<const MapPoint*, std::size_t> point_index;
  const std::size_t num_window = keyframes.size();
  for (std::size_t k = 0; k < num_window; ++k) {
    for (const MapPointPtr& mp : keyframes[k]->map_points()) {
      if (!mp || mp->is_bad() || !point_index.emplace(mp.get(), points.size()).second) continue;
      points.push_back(mp);
      ba_points.push_back({mp->id(), mp->position()});
    }
  }
  for (const MapPointPtr& mp : points) {
    for (const auto& [k, idx] : mp->observations()) {
      if (!k->is_bad()) add_keyframe(k, true);
    }
  }
  std::vector<BaObservation> observations;
  std::vector<std::pair<KeyFrame*, MapPointPtr>> observed;
  const ScalePyramid& pyramid = query.setup().pyramid;
  for (std::size_t p = 0; p < points.size(); ++p) {
    for (const auto& [k, idx] : points[p]->observations()) {
      const auto it = kf_index.find(k);
      if (it == kf_index.end()) continue;
      const cv::KeyPoint& kp = k->keypoint(idx);
      BaObservation o;
      o.keyframe = it->second;
      o.point = p;
      o.pixel = Eigen::Vector2d(kp.pt.x, kp.pt.y);
      o.u_right = k->u_right(idx);
      o.inv_sigma2 = pyramid.inv_sigma2[static_cast<std::size_t>(kp.octave)];
      observations.push_back(o);
      observed.emplace_back(k, points[p]);
    }
  }
  const BundleAdjustmentResult r =
      bundle_adjust(query.setup().camera, ba_keyframes, ba_points, observations, options);
  for (std::size_t k = 0; k < keyframes.size(); ++k) {
    if (ba_keyframes[k].fixed) {
      ++stats.welding_fixed_keyframes;
      continue;
    }
    keyframes[k]->set_pose(r.T_cam_world[k]);
    free_keyframes.insert(keyframes[k]);
    ++stats.welding_keyframes;
  }
  for (std::size_t p = 0; p < points.size(); ++p) {
    points[p]->set_position(r.points[p]);
    adjusted_points.insert(points[p].get());
  }
  for (std::size_t o = 0; o < observations.size(); ++o) {
    if (r.observation_inlier[o]) continue;
    auto& [k, mp] = observed[o];
    const std::ptrdiff_t idx = mp->index_in(k);
    if (idx < 0) continue;
    k->erase_map_point(static_cast<std::size_t>(idx));
    mp->erase_observation(k);
    ++stats.welding_outliers;
  }
}

// Step 5: the source keyframes outside the window follow it.
void propagate_correction(Map& source, const std::unordered_set<const KeyFrame*>& window,
                          const PoseById& before, int strong_weight, int iterations, MapMergeStats& stats) {
  const std::vector<KeyFramePtr> keyframes = source.keyframes();
  std::unordered_map<const KeyFrame*, std::size_t> node;
  std::vector<Eigen::Isometry3d> T_world_node;
  std::vector<std::size_t> fixed;
  for (const KeyFramePtr& kf : keyframes) {
    if (window.count(kf.get())) fixed.push_back(T_world_node.size());
    node.emplace(kf.get(), T_world_node.size());
    T_world_node.push_back(kf->T_world_cam());
  }
  if (fixed.size() == keyframes.size()) return;
  std::vector<PoseGraphEdge> edges;
  std::set<std::pair<std::size_t, std::size_t>> added;
  auto add_edge = [&](const KeyFrame* a, const KeyFrame* b) {
    const auto ia = node.find(a), ib = node.find(b);
    if (ia == node.end() || ib == node.end() || a == b) return;
    if (!added.insert(std::minmax(ia->second, ib->second)).second) return;
    PoseGraphEdge e;
    e.from = ia->second;
    e.to = ib->second;
    e.T_from_to = before.at(a->id()).inverse() * before.at(b->id());
    edges.push_back(e);
  };
  for (const KeyFramePtr& kf : keyframes) {
    if (kf->parent() && !kf->parent()->is_bad()) add_edge(kf->parent(), kf.get());
    for (KeyFrame* n : kf->covisibles_with_weight(strong_weight)) {
      if (!n->is_bad()) add_edge(kf.get(), n);
    }
  }
  stats.graph_nodes = static_cast<int>(T_world_node.size());
  stats.graph_edges = static_cast<int>(edges.size());
  const std::vector<Eigen::Isometry3d> optimized =
      optimize_pose_graph(std::move(T_world_node), edges, fixed, iterations);
  for (std::size_t k = 0; k < keyframes.size(); ++k) keyframes[k]->set_pose(optimized[k].inverse());
}

}  // namespace

MapMergeStats merge_maps(Map& target, Map& source, const LoopDetection& detection, const MapMergerOptions& options) {
  options.check();
  MapMergeStats stats;
  KeyFrame& query = *detection.query;
  stats.target_map = target.id();
  stats.source_map = source.id();
  stats.query_id = query.id();
  stats.loop_id = detection.loop->id();
  stats.inliers = detection.inliers;

  // 1. Rigid move of the whole source map.
  const Eigen::Isometry3d T_target_source = detection.T_world_query_corrected * query.T_cam_world();
  const Eigen::Isometry3d T_source_target = T_target_source.inverse();
  stats.T_target_source = T_target_source;
  std::unordered_set<const KeyFrame*> source_keyframes;
  for (const KeyFramePtr& kf : source.all_keyframes()) {
    kf->set_pose(kf->T_cam_world() * T_source_target);
    kf->set_origin(false);
    source_keyframes.insert(kf.get());
    stats.moved_keyframes += kf->is_bad() ? 0 : 1;
  }
  const std::vector<MapPointPtr> source_points = source.map_points();
  for (const MapPointPtr& mp : source_points) mp->set_position(T_target_source * mp->position());
  stats.moved_points = static_cast<int>(source_points.size());

  // 2. One spanning tree.
  reroot_spanning_tree(query, *detection.loop);

  // 3. Fusion across the seam.
  stats.fused_points = fuse_seam(query, detection, options.fuse_window);

  // 4. Welding BA; poses before it define the graph edges of step 5.
  PoseById before;
  std::unordered_map<std::uint64_t, Eigen::Isometry3d> T_cam_world_before;
  for (const KeyFramePtr& kf : source.all_keyframes()) {
    before.emplace(kf->id(), kf->T_world_cam());
    T_cam_world_before.emplace(kf->id(), kf->T_cam_world_resolved());
  }
  std::unordered_set<const KeyFrame*> window;
  std::unordered_set<const MapPoint*> adjusted;
  welding_bundle_adjustment(query, source_keyframes, options.welding_bundle_adjustment, stats, window, adjusted);

  // 5. The rest follows; points not in the BA move with their reference keyframe.
  propagate_correction(source, window, before, options.strong_covisibility_weight, options.pose_graph_iterations,
                       stats);
  std::unordered_map<std::uint64_t, const KeyFrame*> by_id;
  for (const KeyFramePtr& kf : source.all_keyframes()) by_id.emplace(kf->id(), kf.get());
  const ScalePyramid& pyramid = query.setup().pyramid;
  for (const MapPointPtr& mp : source_points) {
    if (mp->is_bad()) continue;
    if (!adjusted.count(mp.get())) {
      const auto it = by_id.find(mp->first_keyframe_id());
      if (it != by_id.end()) {
        const KeyFrame* ref = it->second;
        mp->set_position(ref->T_cam_world_resolved().inverse() * (T_cam_world_before.at(ref->id()) * mp->position()));
      }
    }
    mp->update_normal_and_depth(pyramid);
  }

  // 6. One map.
  target.absorb(source);

  // 7. Global BA (the oldest keyframe, the target's origin, fixed).
  if (options.global_bundle_adjustment) {
    const GlobalBundleAdjustmentProblem problem = snapshot_global_problem(target);
    const BundleAdjustmentResult result = solve_global_problem(problem, options.global_bundle_adjustment_options);
    apply_global_result(target, problem, result);
    stats.global_bundle_adjustment = !result.aborted;
  }
  return stats;
}

void MapMergerOptions::check() const {
  using namespace option_check;
  detector.check();
  above("MapMergerOptions.fuse_window", fuse_window, 0);
  welding_bundle_adjustment.check();
  at_least("MapMergerOptions.strong_covisibility_weight", strong_covisibility_weight, 0);
  at_least("MapMergerOptions.pose_graph_iterations", pose_graph_iterations, 1);
  global_bundle_adjustment_options.check();
}

}  // namespace stillslam
