#pragma once
// Loop correction for RGB-D/stereo (scale fixed), after ORB-SLAM's
// CorrectLoop: propagate the query keyframe's corrected pose to its
// covisible neighbours and their points, fuse the loop's map points, then
// optimize the essential graph (spanning tree + strong covisibility edges +
// loop edges, the loop keyframe fixed) and move every map point with its
// reference keyframe's correction. The caller holds the map's update mutex
// and has stopped anything else that writes poses (local BA).
#include <cstdint>
#include <set>
#include <utility>

#include "stillslam/loop/loop_detector.h"
#include "stillslam/map/map.h"

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
};

// Loop edges (keyframe id pairs) kept across closures: later essential-graph
// optimizations keep earlier loops closed.
using LoopEdges = std::set<std::pair<std::uint64_t, std::uint64_t>>;

LoopCorrectionStats correct_loop(Map& map, const LoopDetection& detection, LoopEdges& loop_edges,
                                 const LoopCorrectionOptions& options = {});

}  // namespace stillslam
