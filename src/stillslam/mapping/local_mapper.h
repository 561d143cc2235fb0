#pragma once
// Local mapping: for each new keyframe — register it (observations,
// covisibility), cull recent points, triangulate new points with neighbours,
// fuse duplicates, run local BA, cull redundant keyframes. A keyframe whose
// provisional points were confirmed later (tracking/provisional_points.h)
// comes back for the fusion of those points alone.
//
// A pipeline stage (core/worker.h): threaded, tracking inserts keyframes and
// can interrupt a running BA when it needs to hand over another one;
// synchronous (deterministic runs and tests), insert only queues and the owner
// calls process_pending() after each tracked frame, outside the map lock.
// The mapper works on one map at a time; switch_map() moves it to another
// (the atlas' new or merged map) once it is idle.
#include <atomic>
#include <mutex>
#include <optional>
#include <vector>

#include "stillslam/core/worker.h"
#include "stillslam/map/map.h"
#include "stillslam/mapping/local_mapper_options.h"

namespace stillslam {

class LocalMapper {
 public:
  LocalMapper(Map& map, LocalMapperOptions options);
  ~LocalMapper();  // stop()
  LocalMapper(const LocalMapper&) = delete;
  LocalMapper& operator=(const LocalMapper&) = delete;

  // Called by tracking (possibly while it holds the map lock).
  void insert_keyframe(KeyFramePtr kf);
  // A keyframe already processed whose provisional points were just
  // confirmed: queued like a keyframe, then its points are fused with its
  // neighbours' as a new keyframe's are (duplicates merged, observations
  // added, which tracking's keyframe decision counts). Nothing else runs.
  void fuse_confirmed(KeyFramePtr kf);
  // At input time `now` (the frame's timestamp, seconds). Threaded: nothing
  // queued or in progress. Synchronous: always. With the busy model in use
  // (options.busy_model; busy_model_threaded for threaded runs) the modelled
  // mapper must be idle as well.
  bool accepts_keyframes(double now) const;
  // Keyframes waiting: the real queue's, or the model's when it has more.
  std::size_t queued_keyframes(double now) const;
  // Tracking needs the queued keyframe at once: the BA in progress stops.
  void interrupt_bundle_adjustment() { abort(BundleAdjustmentAbort::Tracking); }

  // Synchronous mode: processes every queued keyframe now (no-op when threaded).
  void process_pending() { worker_.run_pending(); }
  // Waits until the queue is empty and the current keyframe is done.
  void flush() { worker_.wait_idle(); }
  // Finishes the keyframe in progress and what is queued, joins. Idempotent.
  void stop() { worker_.stop(); }
  // Loop correction: pause() lets the keyframe in progress finish (with its
  // BA, or aborting it with options.pause_aborts_bundle_adjustment), then
  // keeps the worker from starting another one and returns once it is idle;
  // resume() lets it continue. Keyframes inserted meanwhile queue up. No-ops
  // in synchronous mode (the owner's thread is the worker).
  void pause();
  void resume() { worker_.resume(); }
  // pause() was called (it may still be waiting for the keyframe in progress).
  bool paused() const { return worker_.paused(); }
  // Works on `map` from now on (flushes first; the recent points of the old
  // map are forgotten).
  void switch_map(Map& map);

  LocalMapperStats stats() const;

 private:
  // A new keyframe, or (fuse_only) one whose confirmed points need fusing.
  struct Job {
    KeyFramePtr kf;
    bool fuse_only = false;
  };
  void process(const KeyFramePtr& kf);
  void fuse(const KeyFramePtr& kf);
  // Sets abort_ba_; the first cause since the keyframe started is kept.
  void abort(BundleAdjustmentAbort cause);
  // The keyframe may have a local BA under options_.bundle_adjustments_per_second.
  bool bundle_adjustment_due(const KeyFrame& kf) const;

  bool uses_busy_model() const { return options_.busy_model && (!options_.threaded || options_.busy_model_threaded); }

  Map* map_;  // changed only by switch_map(), while the worker is idle
  LocalMapperOptions options_;
  mutable std::mutex busy_mutex_;
  MapperBusyModel busy_model_;  // fed by process(), read by tracking
  std::atomic<bool> abort_ba_{false};
  std::atomic<BundleAdjustmentAbort> abort_cause_{BundleAdjustmentAbort::None};
  std::vector<MapPointPtr> recent_points_;
  std::optional<double> last_bundle_adjustment_timestamp_;  // of the last local BA's keyframe (mapping thread only)
  mutable std::mutex stats_mutex_;
  LocalMapperStats stats_;
  Worker<Job> worker_;  // last: its thread starts after the members above exist
};

}  // namespace stillslam
