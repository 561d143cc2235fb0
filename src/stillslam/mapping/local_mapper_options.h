#pragma once
// Settings of local mapping (mapping/local_mapper.h) and the statistics it reports.
#include <cstdint>
#include <functional>
#include <vector>

#include "stillslam/map/keyframe.h"
#include "stillslam/mapping/keyframe_culling.h"
#include "stillslam/mapping/local_window_options.h"
#include "stillslam/mapping/neighbour_fusion.h"
#include "stillslam/mapping/point_culling.h"
#include "stillslam/mapping/point_triangulation.h"
#include "stillslam/optimize/bundle_adjustment.h"

namespace stillslam {

struct LocalMapperOptions {
  bool threaded = true;
  PointCullingOptions point_culling;
  PointTriangulationOptions triangulation;
  FusionOptions fusion;
  KeyFrameCullingOptions keyframe_culling;
  BundleAdjustmentOptions bundle_adjustment = default_bundle_adjustment();
  LocalWindowOptions window;
  bool enable_bundle_adjustment = true;
  bool enable_keyframe_culling = true;
  // Wired by System (both optional). Called outside the map lock: every
  // finished keyframe (to loop closing) and the ids of culled keyframes (to
  // drop them from place recognition).
  std::function<void(KeyFramePtr)> on_keyframe_processed;
  std::function<void(std::uint64_t)> on_keyframe_culled;

  static BundleAdjustmentOptions default_bundle_adjustment() {
    BundleAdjustmentOptions o;
    o.iterations = 5;  // ORB-SLAM: 5 robust iterations, then 10 without outliers
    o.outlier_rounds = 1;
    o.iterations_after_outliers = 10;
    // The window was optimized a keyframe ago: stop once an iteration gains
    // less than 0.01 % (bench/README.md, 2026-12-02: 1e-3 saves a little more
    // CPU but lost accuracy on the demo).
    o.function_tolerance = 1e-4;
    return o;
  }
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

// One local BA: its window, Ceres iterations and cost (wall and mapping-thread CPU).
struct LocalBundleAdjustmentRecord {
  int keyframes = 0, fixed_keyframes = 0, points = 0, observations = 0;
  int iterations = 0;
  double ms = 0, cpu_ms = 0;
  bool aborted = false;
};

struct LocalMapperStats {
  int keyframes = 0;
  int points_created = 0;
  int points_culled = 0;
  int keyframes_culled = 0;
  int bundle_adjustments = 0;
  int bundle_adjustments_aborted = 0;
  int bundle_adjustments_skipped = 0;  // hurried keyframes (see local_mapper.cpp)
  double bundle_adjustment_ms = 0;  // total
  double total_ms = 0;              // total processing time
  double cpu_ms = 0;                // mapping thread's CPU time (Ceres threads beyond the first not counted)
  std::vector<LocalBundleAdjustmentRecord> bundle_adjustment_runs;  // in order

  LocalMapperStats& operator+=(const LocalMapperStats& o) {
    keyframes += o.keyframes;
    points_created += o.points_created;
    points_culled += o.points_culled;
    keyframes_culled += o.keyframes_culled;
    bundle_adjustments += o.bundle_adjustments;
    bundle_adjustments_aborted += o.bundle_adjustments_aborted;
    bundle_adjustments_skipped += o.bundle_adjustments_skipped;
    bundle_adjustment_ms += o.bundle_adjustment_ms;
    total_ms += o.total_ms;
    cpu_ms += o.cpu_ms;
    bundle_adjustment_runs.insert(bundle_adjustment_runs.end(), o.bundle_adjustment_runs.begin(),
                                  o.bundle_adjustment_runs.end());
    return *this;
  }
};

}  // namespace stillslam
