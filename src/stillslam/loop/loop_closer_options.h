#pragma once
// Settings of loop closing (loop/loop_closer.h) and the statistics it reports.
#include <functional>

#include "stillslam/loop/loop_correction.h"
#include "stillslam/loop/loop_detector.h"
#include "stillslam/optimize/bundle_adjustment.h"

namespace stillslam {

struct LoopCloserOptions {
  bool threaded = true;
  bool detect_loops = true;  // false: only index keyframes for relocalization
  LoopDetectorOptions detector;
  LoopCorrectionOptions correction;
  bool run_global_bundle_adjustment = true;
  // stop() lets a running global BA finish and apply (ORB-SLAM3's shutdown
  // waits for it too): a loop closed shortly before the end of a run would
  // otherwise leave only the essential-graph correction in the output
  // (rendered loop: ATE 0.092 m instead of 0.034 m). false: stop() aborts it.
  bool finish_global_bundle_adjustment_on_stop = true;
  BundleAdjustmentOptions global_bundle_adjustment = default_global_bundle_adjustment();
  // Wired by System: local mapping must not write poses while a loop is
  // corrected (its BA works on copies outside the lock). Both optional.
  std::function<void()> pause_local_mapping;   // returns once local mapping is idle and paused
  std::function<void()> resume_local_mapping;

  static BundleAdjustmentOptions default_global_bundle_adjustment() {
    BundleAdjustmentOptions o;
    o.iterations = 10;  // ORB-SLAM: 10 iterations after a loop
    o.outlier_rounds = 0;
    return o;
  }
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

struct LoopCloserStats {
  int keyframes = 0;
  int loops_closed = 0;
  int global_bundle_adjustments = 0;
  int global_bundle_adjustments_aborted = 0;
  double detection_ms = 0;   // total: BoW query, consistency and geometry
  double correction_ms = 0;  // total
  double global_bundle_adjustment_ms = 0;

  LoopCloserStats& operator+=(const LoopCloserStats& o) {
    keyframes += o.keyframes;
    loops_closed += o.loops_closed;
    global_bundle_adjustments += o.global_bundle_adjustments;
    global_bundle_adjustments_aborted += o.global_bundle_adjustments_aborted;
    detection_ms += o.detection_ms;
    correction_ms += o.correction_ms;
    global_bundle_adjustment_ms += o.global_bundle_adjustment_ms;
    return *this;
  }
};

}  // namespace stillslam
