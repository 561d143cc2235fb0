#pragma once
// Loop correction for RGB-D/stereo (scale fixed), after ORB-SLAM's
// CorrectLoop: propagate the query keyframe's corrected pose to its
// covisible neighbours and their points, fuse the loop's map points, then
// optimize the essential graph (spanning tree + strong covisibility edges +
// loop edges, the loop keyframe fixed) and move every map point with its
// reference keyframe's correction.
//
// In three steps, so that the essential-graph optimization can run without
// the map lock:
//   begin   (lock): neighbourhood correction, fusion, loop links, and the
//           essential graph with every keyframe's pose before optimization;
//   solve   (no lock): the pose-graph optimization on that copy;
//   finish  (lock): optimized poses written back (keyframes culled meanwhile
//           left to their spanning-tree parent), keyframes created meanwhile
//           moved with their spanning-tree parent's correction (the query's
//           when local mapping has not given them a parent yet), every point
//           with its reference keyframe's.
// correct_loop() runs the three in a row. The caller holds the map's update
// mutex where stated and has stopped anything else that writes poses of
// existing keyframes (local BA) from begin to finish.
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <set>
#include <unordered_map>
#include <utility>
#include <vector>

#include "stillslam/loop/loop_detector.h"
#include "stillslam/map/map.h"
#include "stillslam/optimize/pose_graph.h"

namespace stillslam {

struct LoopCorrectionOptions {
  float fuse_window = 4.f;              // pixels at level 0 (ORB-SLAM: 4)
  int strong_covisibility_weight = 100;  // covisibility edges of the essential graph
  int pose_graph_iterations = 20;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

struct LoopCorrectionStats {
  int corrected_keyframes = 0;  // the query's neighbourhood moved in one piece
  int fused_points = 0;
  int new_loop_links = 0;       // covisibility links created by fusion
  int graph_nodes = 0;
  int graph_edges = 0;
  int propagated_keyframes = 0;  // created between begin and finish, moved with their parent
};

// Loop edges (keyframe id pairs) kept across closures: later essential-graph
// optimizations keep earlier loops closed.
using LoopEdges = std::set<std::pair<std::uint64_t, std::uint64_t>>;

// What begin_loop_correction leaves for solve and finish.
struct LoopCorrectionProblem {
  // The essential graph over the keyframes active at begin (node order).
  std::vector<KeyFramePtr> keyframes;
  std::vector<Eigen::Isometry3d> T_world_node;  // initial values
  std::vector<PoseGraphEdge> edges;
  std::vector<std::size_t> fixed;  // the loop keyframe
  int iterations = 20;
  // Every keyframe's (also culled ones') resolved pose before the
  // optimization, by id: points move from it to the optimized pose.
  std::unordered_map<std::uint64_t, Eigen::Isometry3d> T_cam_world_before;
  // Points moved with the query's neighbourhood: the keyframe that moved
  // them (one of `connected`) is their reference in finish (others use their
  // first keyframe).
  std::unordered_map<MapPointPtr, KeyFrame*> corrected_by;
  std::vector<KeyFramePtr> connected;  // the query's corrected neighbourhood, query first
  std::uint64_t query_id = 0, loop_id = 0;
  LoopCorrectionStats stats;
};

LoopCorrectionStats correct_loop(Map& map, const LoopDetection& detection, LoopEdges& loop_edges,
                                 const LoopCorrectionOptions& options = {});

// Caller holds the lock.
LoopCorrectionProblem begin_loop_correction(Map& map, const LoopDetection& detection, const LoopEdges& loop_edges,
                                            const LoopCorrectionOptions& options = {});
// No lock: reads only the problem. T_world per node.
std::vector<Eigen::Isometry3d> solve_loop_correction(const LoopCorrectionProblem& problem);
// Caller holds the lock; adds the loop to loop_edges. Returns the stats with
// propagated_keyframes (keyframes created between begin and finish).
LoopCorrectionStats finish_loop_correction(Map& map, const LoopCorrectionProblem& problem,
                                           const std::vector<Eigen::Isometry3d>& T_world_node, LoopEdges& loop_edges);

}  // namespace stillslam
