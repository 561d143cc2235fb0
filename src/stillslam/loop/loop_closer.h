#pragma once
// The loop-closing stage: consumes keyframes from local mapping, detects
// loops (loop_detector.h), corrects them (loop_correction.h), indexes each
// keyframe for place recognition, and refines the whole map with a global
// bundle adjustment in a background thread that a newer loop aborts.
//
// A pipeline stage (core/worker.h): threaded, its worker thread consumes the
// queue; synchronous (deterministic runs and tests), submit() only queues and
// the owner calls process_pending(), which also runs the global BA inline.
// It works on one map at a time; switch_map() moves it to another.
#include <atomic>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

#include "stillslam/core/worker.h"
#include "stillslam/loop/loop_closer_options.h"
#include "stillslam/loop/loop_correction.h"
#include "stillslam/loop/loop_detector.h"
#include "stillslam/loop/place_recognizer.h"
#include "stillslam/map/map.h"

namespace stillslam {

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
  void submit(KeyFramePtr keyframe) { worker_.submit(std::move(keyframe)); }
  // Synchronous mode: processes every queued keyframe (no-op when threaded).
  void process_pending() { worker_.run_pending(); }
  // Waits until the queue is empty and no global BA runs.
  void flush();
  // Processes what is queued, lets a running global BA finish (or aborts it,
  // see finish_global_bundle_adjustment_on_stop), joins. Idempotent.
  void stop();
  // Works on `map` from now on: flushes, then forgets the loop state of the
  // old map (consistency groups, loop edges).
  void switch_map(Map& map);

  bool global_bundle_adjustment_running() const { return gba_running_.load(); }
  LoopCloserStats stats() const;
  std::vector<ClosedLoop> loops() const;

 private:
  void process(const KeyFramePtr& keyframe);
  void start_global_bundle_adjustment();
  void stop_global_bundle_adjustment();
  void global_bundle_adjustment();

  Map* map_;  // changed only by switch_map(), while nothing runs
  PlaceRecognizer& recognizer_;
  LoopCloserOptions options_;
  std::optional<LoopDetector> detector_;  // replaced by switch_map()
  LoopEdges loop_edges_;

  mutable std::mutex stats_mutex_;
  LoopCloserStats stats_;
  std::vector<ClosedLoop> loops_;

  std::mutex gba_mutex_;  // guards gba_thread_ (started by the worker, joined by flush/stop too)
  std::atomic<bool> gba_abort_{false};
  std::atomic<bool> gba_running_{false};
  std::thread gba_thread_;
  Worker<KeyFramePtr> worker_;  // last: its thread starts after the members above exist
};

}  // namespace stillslam
