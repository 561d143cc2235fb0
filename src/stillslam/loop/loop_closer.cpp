#include "stillslam/loop/loop_closer.h"

#include "stillslam/core/stopwatch.h"
#include "stillslam/loop/global_bundle_adjustment.h"
#include "stillslam/loop/loop_snapshot.h"

namespace stillslam {

LoopCloser::LoopCloser(Map& map, PlaceRecognizer& recognizer, LoopCloserOptions options)
    : map_(&map),
      recognizer_(recognizer),
      options_(std::move(options)),
      detector_(std::in_place, recognizer, options_.detector),
      worker_(options_.threaded ? WorkerMode::Threaded : WorkerMode::Synchronous,
              [this](KeyFramePtr& kf) { process(kf); }) {
  options_.check();
}

LoopCloser::~LoopCloser() { stop(); }

void LoopCloser::flush() {
  worker_.wait_idle();
  std::lock_guard<std::mutex> lock(gba_mutex_);
  if (gba_thread_.joinable()) gba_thread_.join();
}

void LoopCloser::stop() {
  worker_.stop();
  if (options_.finish_global_bundle_adjustment_on_stop) {
    std::lock_guard<std::mutex> lock(gba_mutex_);
    if (gba_thread_.joinable()) gba_thread_.join();
  } else {
    stop_global_bundle_adjustment();
  }
}

void LoopCloser::switch_map(Map& map) {
  flush();
  map_ = &map;
  detector_.emplace(recognizer_, options_.detector);
  loop_edges_.clear();
}

void LoopCloser::process(const KeyFramePtr& keyframe) {
  // Detection: candidates and a snapshot under the map lock, verification on
  // the snapshot without it (tracking runs meanwhile), a re-check under it.
  Stopwatch detection_time;
  std::optional<LoopSnapshot> snapshot;
  {
    std::lock_guard<std::mutex> lock(map_->update_mutex());
    if (keyframe->is_bad()) return;
    if (options_.detect_loops) snapshot = detector_->prepare(*map_, *keyframe);
    recognizer_.add(*keyframe);
  }
  std::optional<LoopDetection> detection = snapshot ? detector_->verify(*snapshot) : std::nullopt;
  const double detection_ms = detection_time.elapsed_ms();

  // Correction: local mapping paused (its BA works on copies and would write
  // back stale poses), a running global BA stopped; the essential graph is
  // solved without the map lock, between a begin and a finish under it.
  std::optional<ClosedLoop> closed;
  double correction_ms = 0;
  if (detection) {
    stop_global_bundle_adjustment();
    if (options_.pause_local_mapping) options_.pause_local_mapping();
    Stopwatch correction_time;
    std::unique_lock<std::mutex> lock(map_->update_mutex());
    // Local mapping may have culled either keyframe or some points meanwhile.
    if ((detection = detector_->recheck(*map_, std::move(*detection)))) {
      const LoopCorrectionProblem problem = begin_loop_correction(*map_, *detection, loop_edges_, options_.correction);
      lock.unlock();
      const std::vector<Eigen::Isometry3d> solved = solve_loop_correction(problem);
      lock.lock();
      closed = ClosedLoop{detection->query->id(), detection->loop->id(), detection->inliers,
                          finish_loop_correction(*map_, problem, solved, loop_edges_)};
      detector_->loop_closed(keyframe->id());
    }
    lock.unlock();
    correction_ms = correction_time.elapsed_ms();
    if (options_.resume_local_mapping) options_.resume_local_mapping();
  }
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.keyframes;
    stats_.detection_ms += detection_ms;
    stats_.correction_ms += correction_ms;
    if (closed) {
      ++stats_.loops_closed;
      loops_.push_back(*closed);
    }
  }
  if (closed && options_.run_global_bundle_adjustment) start_global_bundle_adjustment();
}

void LoopCloser::start_global_bundle_adjustment() {
  std::lock_guard<std::mutex> lock(gba_mutex_);
  gba_abort_ = true;
  if (gba_thread_.joinable()) gba_thread_.join();
  gba_abort_ = false;
  gba_running_ = true;
  if (options_.threaded) {
    gba_thread_ = std::thread([this] { global_bundle_adjustment(); });
  } else {
    global_bundle_adjustment();
  }
}

void LoopCloser::stop_global_bundle_adjustment() {
  std::lock_guard<std::mutex> lock(gba_mutex_);
  gba_abort_ = true;
  if (gba_thread_.joinable()) gba_thread_.join();
}

void LoopCloser::global_bundle_adjustment() {
  Stopwatch time;
  GlobalBundleAdjustmentProblem problem;
  {
    std::lock_guard<std::mutex> lock(map_->update_mutex());
    problem = snapshot_global_problem(*map_);
  }
  BundleAdjustmentOptions options = options_.global_bundle_adjustment;
  options.abort = &gba_abort_;
  const BundleAdjustmentResult result = solve_global_problem(problem, options);
  const bool aborted = result.aborted || gba_abort_.load();
  if (!aborted) {
    if (options_.pause_local_mapping) options_.pause_local_mapping();
    {
      std::lock_guard<std::mutex> lock(map_->update_mutex());
      apply_global_result(*map_, problem, result);
    }
    if (options_.resume_local_mapping) options_.resume_local_mapping();
  }
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.global_bundle_adjustments;
    if (aborted) ++stats_.global_bundle_adjustments_aborted;
    stats_.global_bundle_adjustment_ms += time.elapsed_ms();
  }
  gba_running_ = false;
}

LoopCloserStats LoopCloser::stats() const {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_;
}

std::vector<ClosedLoop> LoopCloser::loops() const {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return loops_;
}

}  // namespace stillslam
