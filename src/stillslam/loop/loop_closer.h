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

#include "stillslam/loop/loop_closer_options.h"
#include "stillslam/loop/loop_correction.h"
#include "stillslam/loop/loop_detector.h"
#include "stillslam/loop/place_recognizer.h"
#include "stillslam/map/map.h"
#include "stillslam/optimize/bundle_adjustment.h"

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
