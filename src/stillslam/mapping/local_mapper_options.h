#pragma once
// Settings of local mapping (mapping/local_mapper.h) and the statistics it reports.
#include <cstdint>
#include <functional>
#include <vector>

#include "stillslam/map/keyframe.h"
#include "stillslam/mapping/keyframe_culling.h"
#include "stillslam/mapping/local_window_options.h"
#include "stillslam/mapping/mapper_busy_model.h"
#include "stillslam/mapping/neighbour_fusion.h"
#include "stillslam/mapping/point_culling.h"
#include "stillslam/mapping/point_triangulation.h"
#include "stillslam/optimize/bundle_adjustment.h"

namespace stillslam {

struct LocalMapperOptions {
  bool threaded = true;
  // Threaded: LocalMapping.threadNice, the mapping thread's nice value is
  // raised by this (Linux; 19 at most, core/thread_priority.h), so that
  // tracking gets a core before it. 0: the process's priority.
  int thread_nice = 0;
  PointCullingOptions point_culling;
  PointTriangulationOptions triangulation;
  FusionOptions fusion;
  KeyFrameCullingOptions keyframe_culling;
  BundleAdjustmentOptions bundle_adjustment = default_bundle_adjustment();
  LocalWindowOptions window;
  bool enable_bundle_adjustment = true;
  // Local BAs per second of input (keyframe timestamps), 0: every keyframe.
  // A keyframe less than 1 / bundle_adjustments_per_second seconds after the
  // last local BA's keyframe gets none (counted as skipped); the next BA's
  // window holds it. Lets more keyframes in at a bounded BA cost.
  double bundle_adjustments_per_second = 0;
  bool enable_keyframe_culling = true;
  // Loop closing's pause(): false lets the keyframe in progress finish with
  // its BA (the loop waits for it); true aborts that BA, as before 2026-12-02
  // (bench/README.md, issue #21: nearly all aborted BAs were these).
  bool pause_aborts_bundle_adjustment = false;
  // An interrupt stops the running local BA only once it has done this many
  // solver iterations (0: at once), so that it has a step to keep
  // (bundle_adjustment.keep_progress_on_abort) instead of nothing.
  int iterations_before_interrupt = 1;
  // Keyframe admission asks a model of how long the mapper would be busy
  // (mapping/mapper_busy_model.h) in synchronous runs, which otherwise never
  // look busy; busy_model_threaded: in threaded runs too (on top of the real
  // mapper's state).
  bool busy_model = true;
  bool busy_model_threaded = false;
  MapperBusyModelOptions busy;
  // Wired by System (both optional). Called outside the map lock: every
  // finished keyframe (to loop closing) and the ids of culled keyframes (to
  // drop them from place recognition).
  std::function<void(KeyFramePtr)> on_keyframe_processed;
  std::function<void(std::uint64_t)> on_keyframe_culled;
  // Tests: called on the mapping thread just before each local BA solve.
  std::function<void()> on_bundle_adjustment_start;

  static BundleAdjustmentOptions default_bundle_adjustment() {
    BundleAdjustmentOptions o;
    o.iterations = 5;  // ORB-SLAM: 5 robust iterations, then 10 without outliers
    o.outlier_rounds = 1;
    o.iterations_after_outliers = 10;
    // The window was optimized a keyframe ago: stop once an iteration gains
    // less than 0.01 % (bench/README.md, 2026-12-02: 1e-3 saves a little more
    // CPU but lost accuracy on the demo).
    o.function_tolerance = 1e-4;
    // An interrupted BA keeps what it reached (ORB-SLAM does too).
    o.keep_progress_on_abort = true;
    // The hand-written Schur solver: the same answers as Ceres at a fraction
    // of the CPU (bench/README.md, "Issue #21, session 9").
    o.solver = BaSolver::Schur;
    // Stereo/RGB-D observations stay split into 2-row blocks: one 3-row block
    // is 13-24 % cheaper per BA but lost accuracy on the held-out renders
    // (bench/README.md, "Lead, session 6": 1.28x and 1.19x ATE).
    return o;
  }
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

// Why a local BA stopped early.
enum class BundleAdjustmentAbort { None, Tracking, Pause };
const char* to_string(BundleAdjustmentAbort cause);

// One local BA: its window, solver iterations and cost (wall and mapping-thread CPU).
struct LocalBundleAdjustmentRecord {
  int keyframes = 0, fixed_keyframes = 0, points = 0, observations = 0;
  int iterations = 0;
  double ms = 0, cpu_ms = 0;
  bool aborted = false;
  // Aborted with some accepted steps applied to the map (cut short) rather
  // than none (discarded).
  bool cut_short = false;
  BundleAdjustmentAbort abort_cause = BundleAdjustmentAbort::None;
};

// Mapping-thread CPU time by step, totals over the keyframes [ms].
struct LocalMapperCpu {
  double registration = 0;       // observations, covisibility, recent point culling
  double triangulation = 0;      // new points with the neighbours
  double fusion = 0;             // duplicates with the neighbours
  double bundle_adjustment = 0;  // gather, solve, apply
  double keyframe_culling = 0;   // redundant keyframes, bad points
  LocalMapperCpu& operator+=(const LocalMapperCpu& o) {
    registration += o.registration;
    triangulation += o.triangulation;
    fusion += o.fusion;
    bundle_adjustment += o.bundle_adjustment;
    keyframe_culling += o.keyframe_culling;
    return *this;
  }
};

struct LocalMapperStats {
  int keyframes = 0;
  int points_created = 0;
  int points_culled = 0;
  int keyframes_culled = 0;
  int bundle_adjustments = 0;
  int bundle_adjustments_aborted = 0;
  int bundle_adjustments_aborted_by_tracking = 0;  // tracking needed a keyframe at once
  int bundle_adjustments_aborted_by_pause = 0;     // loop closing paused the mapper
  int bundle_adjustments_cut_short = 0;  // aborted, the progress so far applied
  int bundle_adjustments_discarded = 0;  // aborted before any accepted step was kept
  int bundle_adjustments_skipped = 0;  // hurried keyframes (see local_mapper.cpp) and those over bundle_adjustments_per_second
  double bundle_adjustment_ms = 0;  // total
  double total_ms = 0;              // total processing time
  double cpu_ms = 0;                // mapping thread's CPU time (Ceres threads beyond the first not counted)
  double modelled_busy_ms = 0;      // the busy model's cost of the keyframes (0 when it is not used)
  LocalMapperCpu cpu_by_step;       // cpu_ms split by step
  std::vector<LocalBundleAdjustmentRecord> bundle_adjustment_runs;  // in order

  LocalMapperStats& operator+=(const LocalMapperStats& o) {
    keyframes += o.keyframes;
    points_created += o.points_created;
    points_culled += o.points_culled;
    keyframes_culled += o.keyframes_culled;
    bundle_adjustments += o.bundle_adjustments;
    bundle_adjustments_aborted += o.bundle_adjustments_aborted;
    bundle_adjustments_aborted_by_tracking += o.bundle_adjustments_aborted_by_tracking;
    bundle_adjustments_aborted_by_pause += o.bundle_adjustments_aborted_by_pause;
    bundle_adjustments_cut_short += o.bundle_adjustments_cut_short;
    bundle_adjustments_discarded += o.bundle_adjustments_discarded;
    bundle_adjustments_skipped += o.bundle_adjustments_skipped;
    bundle_adjustment_ms += o.bundle_adjustment_ms;
    total_ms += o.total_ms;
    cpu_ms += o.cpu_ms;
    modelled_busy_ms += o.modelled_busy_ms;
    cpu_by_step += o.cpu_by_step;
    bundle_adjustment_runs.insert(bundle_adjustment_runs.end(), o.bundle_adjustment_runs.begin(),
                                  o.bundle_adjustment_runs.end());
    return *this;
  }
};

}  // namespace stillslam
