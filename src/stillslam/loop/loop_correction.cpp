#include "stillslam/loop/loop_correction.h"

#include <functional>
#include <map>
#include <unordered_set>

#include "stillslam/core/option_check.h"
#include "stillslam/map/fuse.h"

namespace stillslam {

namespace {

using PoseById = std::unordered_map<std::uint64_t, Eigen::Isometry3d>;
using LoopLinks = std::map<KeyFrame*, std::set<KeyFrame*, KeyFrameIdLess>, KeyFrameIdLess>;

// Essential graph over the active keyframes. Non-loop edges measure the
// relative poses from before the correction (the drifted odometry the
// optimization must bend), loop edges from after it.
void build_essential_graph(const Map& map, const KeyFrame& loop_kf, const PoseById& uncorrected,
                           const LoopLinks& loop_links, const LoopEdges& loop_edges,
                           const LoopCorrectionOptions& options, LoopCorrectionProblem& problem) {
  problem.keyframes = map.keyframes();
  std::unordered_map<const KeyFrame*, std::size_t> node;
  for (const auto& kf : problem.keyframes) {
    node.emplace(kf.get(), problem.T_world_node.size());
    problem.T_world_node.push_back(kf->T_world_cam());
  }
  auto before = [&](const KeyFrame* kf) {
    const auto it = uncorrected.find(kf->id());
    return it != uncorrected.end() ? it->second : kf->T_world_cam();
  };
  std::set<std::pair<std::size_t, std::size_t>> added;
  auto add_edge = [&](const KeyFrame* a, const KeyFrame* b, bool corrected) {
    const auto ia = node.find(a), ib = node.find(b);
    if (ia == node.end() || ib == node.end() || a == b) return;
    const auto key = std::minmax(ia->second, ib->second);
    if (!added.insert(key).second) return;
    PoseGraphEdge e;
    e.from = ia->second;
    e.to = ib->second;
    e.T_from_to = corrected ? a->T_world_cam().inverse() * b->T_world_cam() : before(a).inverse() * before(b);
    problem.edges.push_back(e);
  };
  for (const auto& [kf, links] : loop_links) {
    for (KeyFrame* other : links) add_edge(kf, other, true);
  }
  for (const auto& kf : problem.keyframes) {
    if (kf->parent() && !kf->parent()->is_bad()) add_edge(kf->parent(), kf.get(), false);
    for (const auto& [a, b] : loop_edges) {
      if (a != kf->id()) continue;
      if (auto other = map.keyframe(b)) add_edge(kf.get(), other.get(), false);
    }
    for (KeyFrame* n : kf->covisibles_with_weight(options.strong_covisibility_weight)) {
      if (!n->is_bad()) add_edge(kf.get(), n, false);
    }
  }
  problem.stats.graph_nodes = static_cast<int>(problem.T_world_node.size());
  problem.stats.graph_edges = static_cast<int>(problem.edges.size());
  problem.fixed = {node.at(&loop_kf)};
  problem.iterations = options.pose_graph_iterations;
}

}  // namespace

LoopCorrectionStats correct_loop(Map& map, const LoopDetection& detection, LoopEdges& loop_edges,
                                 const LoopCorrectionOptions& options) {
  const LoopCorrectionProblem problem = begin_loop_correction(map, detection, loop_edges, options);
  return finish_loop_correction(map, problem, solve_loop_correction(problem), loop_edges);
}

LoopCorrectionProblem begin_loop_correction(Map& map, const LoopDetection& detection, const LoopEdges& loop_edges,
                                            const LoopCorrectionOptions& options) {
  LoopCorrectionProblem problem;
  LoopCorrectionStats& stats = problem.stats;
  KeyFrame& query = *detection.query;
  const ScalePyramid& pyramid = query.setup().pyramid;
  query.update_connections();

  // 1. The query's neighbourhood moves rigidly with the query.
  std::vector<KeyFrame*> connected{&query};
  for (KeyFrame* k : query.covisibles()) {
    if (!k->is_bad()) connected.push_back(k);
  }
  const Eigen::Isometry3d T_query_world_old = query.T_cam_world();
  PoseById uncorrected;
  auto& corrected_by = problem.corrected_by;
  for (KeyFrame* k : connected) {
    const Eigen::Isometry3d T_world_k_old = k->T_world_cam();
    const Eigen::Isometry3d T_world_k_new = detection.T_world_query_corrected * T_query_world_old * T_world_k_old;
    uncorrected.emplace(k->id(), T_world_k_old);
    for (const MapPointPtr& mp : k->map_points()) {
      if (!mp || mp->is_bad() || !corrected_by.emplace(mp, k).second) continue;
      mp->set_position(T_world_k_new * (T_world_k_old.inverse() * mp->position()));
    }
    k->set_pose(T_world_k_new.inverse());
  }
  for (const auto& [mp, k] : corrected_by) {
    mp->update_normal_and_depth(pyramid);
  }
  stats.corrected_keyframes = static_cast<int>(connected.size());

  // Neighbours before fusion, to find the links the loop creates.
  LoopLinks previous;
  for (KeyFrame* k : connected) {
    const auto c = k->covisibles();
    previous[k] = std::set<KeyFrame*, KeyFrameIdLess>(c.begin(), c.end());
  }

  // 2. The query's loop matches replace its own points; then the loop points
  // are fused into the whole corrected neighbourhood.
  for (std::size_t i = 0; i < detection.matched_points.size(); ++i) {
    const MapPointPtr& loop_point = detection.matched_points[i];
    if (!loop_point || loop_point->is_bad()) continue;
    const MapPointPtr current = query.map_point(i);
    if (current == loop_point) continue;
    if (current && !current->is_bad()) {
      current->replace_with(loop_point);
    } else {
      loop_point->add_observation(&query, i);
      query.set_map_point(i, loop_point);
      loop_point->compute_distinctive_descriptor();
    }
    ++stats.fused_points;
  }
  for (KeyFrame* k : connected) stats.fused_points += fuse(*k, detection.loop_points, options.fuse_window);

  // 3. New links = neighbours after fusion that were neither neighbours nor
  // part of the corrected neighbourhood.
  const std::unordered_set<const KeyFrame*> connected_set(connected.begin(), connected.end());
  LoopLinks loop_links;
  for (KeyFrame* k : connected) {
    k->update_connections();
    for (KeyFrame* n : k->covisibles()) {
      if (previous[k].count(n) || connected_set.count(n)) continue;
      loop_links[k].insert(n);
      ++stats.new_loop_links;
    }
  }
  loop_links[&query].insert(detection.loop.get());

  // 4. The essential graph, and what finish needs to move the points.
  for (const auto& kf : map.all_keyframes()) problem.T_cam_world_before.emplace(kf->id(), kf->T_cam_world_resolved());
  build_essential_graph(map, *detection.loop, uncorrected, loop_links, loop_edges, options, problem);
  for (KeyFrame* k : connected) problem.connected.push_back(k->shared_from_this());
  problem.query_id = query.id();
  problem.loop_id = detection.loop->id();
  return problem;
}

std::vector<Eigen::Isometry3d> solve_loop_correction(const LoopCorrectionProblem& problem) {
  return optimize_pose_graph(problem.T_world_node, problem.edges, problem.fixed, problem.iterations);
}

LoopCorrectionStats finish_loop_correction(Map& map, const LoopCorrectionProblem& problem,
                                           const std::vector<Eigen::Isometry3d>& T_world_node, LoopEdges& loop_edges) {
  LoopCorrectionStats stats = problem.stats;
  // Keyframes created since begin have not moved: their pose now is their
  // pose before.
  PoseById T_cam_world_before = problem.T_cam_world_before;
  std::vector<KeyFrame*> created;
  for (const auto& kf : map.all_keyframes()) {
    if (T_cam_world_before.emplace(kf->id(), kf->T_cam_world_resolved()).second && !kf->is_bad()) {
      created.push_back(kf.get());
    }
  }
  // Culled since begin: the parent's new pose moves them.
  for (std::size_t k = 0; k < problem.keyframes.size(); ++k) {
    if (!problem.keyframes[k]->is_bad()) problem.keyframes[k]->set_pose(T_world_node[k].inverse());
  }
  // Created since begin: with their spanning-tree parent (parents first). A
  // keyframe local mapping has not connected yet has no parent: tracking made
  // it next to the query, so it follows the query.
  std::unordered_set<const KeyFrame*> pending(created.begin(), created.end());
  KeyFrame* query = problem.connected.front().get();
  std::function<void(KeyFrame*)> propagate = [&](KeyFrame* kf) {
    if (!pending.erase(kf)) return;
    KeyFrame* parent = kf->parent() ? kf->parent() : query;
    const auto parent_before = T_cam_world_before.find(parent->id());
    if (parent_before == T_cam_world_before.end()) return;
    propagate(parent);
    const Eigen::Isometry3d T_kf_parent = kf->T_cam_world() * parent_before->second.inverse();
    kf->set_pose(T_kf_parent * parent->T_cam_world_resolved());
    ++stats.propagated_keyframes;
  };
  for (KeyFrame* kf : created) propagate(kf);

  // Every point follows its reference keyframe.
  const ScalePyramid& pyramid = problem.connected.front()->setup().pyramid;  // the query's
  std::unordered_map<std::uint64_t, const KeyFrame*> by_id;
  for (const auto& kf : map.all_keyframes()) by_id.emplace(kf->id(), kf.get());
  for (const MapPointPtr& mp : map.map_points()) {
    if (mp->is_bad()) continue;
    const auto c = problem.corrected_by.find(mp);
    const KeyFrame* ref = c != problem.corrected_by.end() ? c->second : nullptr;
    if (!ref) {
      const auto it = by_id.find(mp->first_keyframe_id());
      if (it == by_id.end()) continue;
      ref = it->second;
    }
    const Eigen::Isometry3d T_world_ref_new = ref->T_cam_world_resolved().inverse();
    mp->set_position(T_world_ref_new * (T_cam_world_before.at(ref->id()) * mp->position()));
    mp->update_normal_and_depth(pyramid);
  }
  for (const KeyFramePtr& k : problem.connected) {
    if (!k->is_bad()) k->update_connections();
  }
  loop_edges.insert({problem.query_id, problem.loop_id});
  loop_edges.insert({problem.loop_id, problem.query_id});
  return stats;
}

void LoopCorrectionOptions::check() const {
  using namespace option_check;
  above("LoopCorrectionOptions.fuse_window", fuse_window, 0);
  at_least("LoopCorrectionOptions.strong_covisibility_weight", strong_covisibility_weight, 0);
  at_least("LoopCorrectionOptions.pose_graph_iterations", pose_graph_iterations, 1);
}

}  // namespace stillslam
