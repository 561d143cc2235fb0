#pragma once
// The loop-closing stage: consumes keyframes from local mapping, detects
// loops (loop_detector.h), corrects them (loop_correction.h), indexes each
// keyframe for place recognition, and refines the whole map with a global
// bundle adjustment in a background thread that a newer loop aborts.
//
// Threaded mode: a worker thread consumes the queue. Synchronous mode
// (deterministic runs and tests): submit() only queues; the owner calls
// process_pending(), which also runs the global BA inline.
#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "stillslam/loop/loop_correction.h"
#include "stillslam/loop/loop_detector.h"
#include "stillslam/loop/place_recognizer.h"
#include "stillslam/map/map.h"
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

struct ClosedLoop {
  std::uint64_t query_id = 0, loop_id = 0;
  int inliers = 0;
  LoopCorrectionStats correction;
};

class LoopCloser {
 public:
  LoopCloser(Map& map, PlaceRecognizer& recognizer, LoopCloserOptions options);
  ~LoopCloser();  // stop()
  LoopCloser(const LoopCloser&) = delete;
  LoopCloser& operator=(const LoopCloser&) = delete;

  // Called by local mapping when it has finished a keyframe.
  void submit(KeyFramePtr keyframe);
  // Synchronous mode: processes every queued keyframe (no-op when threaded).
  void process_pending();
  // Waits until the queue is empty and no global BA runs.
  void flush();
  // Processes what is queued, lets a running global BA finish (or aborts it,
  // see finish_global_bundle_adjustment_on_stop), joins.
  void stop();

  bool global_bundle_adjustment_running() const { return gba_running_.load(); }
  LoopCloserStats stats() const;
  std::vector<ClosedLoop> loops() const;

 private:
  void run();
  void process(const KeyFramePtr& keyframe);
  void start_global_bundle_adjustment();
  void stop_global_bundle_adjustment();
  void global_bundle_adjustment();

  Map& map_;
  PlaceRecognizer& recognizer_;
  LoopCloserOptions options_;
  LoopDetector detector_;
  LoopEdges loop_edges_;

  mutable std::mutex queue_mutex_;
  std::condition_variable queue_changed_;
  std::deque<KeyFramePtr> queue_;
  bool busy_ = false;
  bool stopping_ = false;

  mutable std::mutex stats_mutex_;
  LoopCloserStats stats_;
  std::vector<ClosedLoop> loops_;

  std::mutex gba_mutex_;  // guards gba_thread_ (started by the worker, joined by flush/stop too)
  std::atomic<bool> gba_abort_{false};
  std::atomic<bool> gba_running_{false};
  std::thread gba_thread_;
  std::thread thread_;  // last: starts after the members above exist
};

}  // namespace stillslam
