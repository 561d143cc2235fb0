#pragma once
// Merging two maps of an atlas after a place was recognized across them
// (merge_detector.h), for RGB-D/stereo (scale known, so SE3):
//  1. the whole source map (the active one) moves rigidly into the target
//     map's frame with T_target_source = T_target_query * T_query_source;
//  2. its spanning tree is re-rooted at the query keyframe, which becomes a
//     child of the recognized keyframe (one tree); the source origin is an
//     ordinary keyframe from now on;
//  3. duplicates are fused: the query's verified matches, then the target's
//     points around the recognized keyframe projected into the query's
//     neighbourhood (new covisibility links across the seam);
//  4. welding bundle adjustment: the query's neighbourhood (source side)
//     free, the recognized keyframe's neighbourhood (target side) and every
//     other observer fixed;
//  5. the rest of the source map follows the window's correction through a
//     pose graph (spanning tree + strong covisibility, window fixed); points
//     move with their reference keyframe;
//  6. keyframes and points move into the target map (Map::absorb);
//  7. optionally a global bundle adjustment of the merged map (inline: the
//     threads are stopped anyway), which spreads the seam's correction over
//     both maps' internal drift.
// The caller holds both maps' update mutexes and has stopped local mapping
// and loop closing of the source map.
#include <cstdint>

#include "stillslam/loop/loop_detector.h"
#include "stillslam/map/map.h"
#include "stillslam/optimize/bundle_adjustment.h"

namespace stillslam {

struct MapMergerOptions {
  LoopDetectorOptions detector;   // candidates, consistency, geometric check
  float fuse_window = 4.f;        // pixels at level 0
  BundleAdjustmentOptions welding_bundle_adjustment = default_welding_bundle_adjustment();
  int strong_covisibility_weight = 100;
  int pose_graph_iterations = 20;
  bool global_bundle_adjustment = true;
  BundleAdjustmentOptions global_bundle_adjustment_options = default_global_bundle_adjustment();

  static BundleAdjustmentOptions default_welding_bundle_adjustment() {
    BundleAdjustmentOptions o;
    o.iterations = 10;
    o.outlier_rounds = 1;
    o.iterations_after_outliers = 10;
    return o;
  }
  static BundleAdjustmentOptions default_global_bundle_adjustment() {
    BundleAdjustmentOptions o;
    o.iterations = 10;  // as after a loop closure
    o.outlier_rounds = 0;
    return o;
  }
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

struct MapMergeStats {
  std::uint64_t target_map = 0, source_map = 0;
  std::uint64_t query_id = 0, loop_id = 0;
  int inliers = 0;  // of the detection
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
  int moved_keyframes = 0, moved_points = 0;
  int fused_points = 0;
  int welding_keyframes = 0, welding_fixed_keyframes = 0, welding_outliers = 0;
  int graph_nodes = 0, graph_edges = 0;
  bool global_bundle_adjustment = false;
};

// `detection` found detection.query (a keyframe of `source`) in `target`.
MapMergeStats merge_maps(Map& target, Map& source, const LoopDetection& detection,
                         const MapMergerOptions& options = {});

}  // namespace stillslam
