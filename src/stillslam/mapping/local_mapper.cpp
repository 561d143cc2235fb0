#include "stillslam/mapping/local_mapper.h"

#include "stillslam/core/stopwatch.h"
#include "stillslam/mapping/keyframe_insertion.h"
#include "stillslam/mapping/local_bundle_adjustment.h"

namespace stillslam {

LocalMapper::LocalMapper(Map& map, LocalMapperOptions options) : map_(map), options_(std::move(options)) {
  if (options_.threaded) thread_ = std::thread([this] { run(); });
}

LocalMapper::~LocalMapper() { stop(); }

void LocalMapper::insert_keyframe(KeyFramePtr kf) {
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    queue_.push_back(std::move(kf));
  }
  abort_ba_ = true;
  queue_changed_.notify_all();
}

std::size_t LocalMapper::queued_keyframes() const {
  std::lock_guard<std::mutex> lock(queue_mutex_);
  return queue_.size();
}

bool LocalMapper::has_new_keyframes() const { return queued_keyframes() > 0; }

void LocalMapper::process_pending() {
  if (options_.threaded) return;
  for (;;) {
    KeyFramePtr kf;
    {
      std::lock_guard<std::mutex> lock(queue_mutex_);
      if (queue_.empty()) return;
      kf = queue_.front();
      queue_.pop_front();
    }
    abort_ba_ = false;
    process(kf);
  }
}

void LocalMapper::flush() {
  if (!options_.threaded) {
    process_pending();
    return;
  }
  std::unique_lock<std::mutex> lock(queue_mutex_);
  queue_changed_.wait(lock, [this] { return (queue_.empty() && !busy_) || !thread_.joinable(); });
}

void LocalMapper::stop() {
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    stopping_ = true;
  }
  queue_changed_.notify_all();
  if (thread_.joinable()) thread_.join();
  process_pending();
}

void LocalMapper::pause() {
  if (!options_.threaded) return;
  std::unique_lock<std::mutex> lock(queue_mutex_);
  paused_ = true;
  abort_ba_ = true;
  queue_changed_.wait(lock, [this] { return !busy_ || !thread_.joinable(); });
}

void LocalMapper::resume() {
  if (!options_.threaded) return;
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    paused_ = false;
  }
  queue_changed_.notify_all();
}

LocalMapperStats LocalMapper::stats() const {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_;
}

void LocalMapper::run() {
  for (;;) {
    KeyFramePtr kf;
    {
      std::unique_lock<std::mutex> lock(queue_mutex_);
      idle_ = true;
      // While paused only a stop gets the worker going again (stop processes what is left).
      queue_changed_.wait(lock, [this] { return stopping_ || (!paused_ && !queue_.empty()); });
      if (queue_.empty()) break;  // stopping and nothing left
      kf = queue_.front();
      queue_.pop_front();
      busy_ = true;
      idle_ = false;
    }
    abort_ba_ = false;
    process(kf);
    {
      std::lock_guard<std::mutex> lock(queue_mutex_);
      busy_ = false;
    }
    queue_changed_.notify_all();
  }
  idle_ = true;
}

void LocalMapper::process(const KeyFramePtr& kf) {
  Stopwatch total;
  LocalMapperStats delta;
  delta.keyframes = 1;
  {
    std::lock_guard<std::mutex> lock(map_.update_mutex());
    kf->set_not_erase(true);
    register_keyframe(*kf, recent_points_);
    delta.points_culled = cull_recent_points(recent_points_, kf->id(), options_.point_culling);
  }
  // Not interruptible by a new keyframe in synchronous mode (determinism).
  const bool threaded = options_.threaded;
  auto new_keyframe_waiting = [this, threaded] { return threaded && has_new_keyframes(); };
  delta.points_created = create_new_points(map_, *kf, recent_points_, options_.triangulation, new_keyframe_waiting);

  if (!new_keyframe_waiting()) {
    std::lock_guard<std::mutex> lock(map_.update_mutex());
    fuse_with_neighbours(*kf, options_.fusion);
  }
  if (!new_keyframe_waiting() && options_.enable_bundle_adjustment) {
    LocalBundleAdjustmentProblem problem;
    {
      std::lock_guard<std::mutex> lock(map_.update_mutex());
      if (map_.num_keyframes() > 2) problem = gather_local_window(*kf);
    }
    if (!problem.keyframes.empty()) {
      Stopwatch ba;
      BundleAdjustmentOptions ba_options = options_.bundle_adjustment;
      ba_options.abort = threaded ? &abort_ba_ : nullptr;
      const BundleAdjustmentResult result = solve_local_window(kf->setup().camera, problem, ba_options);
      {
        std::lock_guard<std::mutex> lock(map_.update_mutex());
        apply_local_window(problem, result);
      }
      delta.bundle_adjustments = 1;
      delta.bundle_adjustments_aborted = result.aborted ? 1 : 0;
      delta.bundle_adjustment_ms = ba.elapsed_ms();
    }
  }
  std::vector<std::uint64_t> culled;
  bool keyframe_alive = false;
  {
    std::lock_guard<std::mutex> lock(map_.update_mutex());
    kf->set_not_erase(false);
    if (options_.enable_keyframe_culling) {
      delta.keyframes_culled = cull_redundant_keyframes(map_, *kf, options_.keyframe_culling, &culled);
    }
    map_.remove_bad_points();
    keyframe_alive = !kf->is_bad();
  }
  if (options_.on_keyframe_culled) {
    for (std::uint64_t id : culled) options_.on_keyframe_culled(id);
  }
  if (options_.on_keyframe_processed && keyframe_alive) options_.on_keyframe_processed(kf);
  delta.total_ms = total.elapsed_ms();
  std::lock_guard<std::mutex> lock(stats_mutex_);
  stats_ += delta;
}

}  // namespace stillslam
