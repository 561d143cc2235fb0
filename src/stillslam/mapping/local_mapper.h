#pragma once
// Local mapping: for each new keyframe — register it (observations,
// covisibility), cull recent points, triangulate new points with neighbours,
// fuse duplicates, run local BA, cull redundant keyframes.
//
// Threaded mode: a worker thread consumes a keyframe queue; tracking inserts
// keyframes and can interrupt a running BA (abort flag) when it needs to hand
// over another one. Synchronous mode (deterministic runs and tests): insert
// only queues, and the owner calls process_pending() after each tracked frame,
// outside the map lock.
#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "stillslam/map/map.h"
#include "stillslam/mapping/local_mapper_options.h"
#include "stillslam/mapping/keyframe_culling.h"
#include "stillslam/mapping/neighbour_fusion.h"
#include "stillslam/mapping/point_culling.h"
#include "stillslam/mapping/point_triangulation.h"
#include "stillslam/optimize/bundle_adjustment.h"

namespace stillslam {

class LocalMapper {
 public:
  LocalMapper(Map& map, LocalMapperOptions options);
  ~LocalMapper();  // stop()
  LocalMapper(const LocalMapper&) = delete;
  LocalMapper& operator=(const LocalMapper&) = delete;

  // Called by tracking (possibly while it holds the map lock).
  void insert_keyframe(KeyFramePtr kf);
  bool accepts_keyframes() const { return !options_.threaded || idle_.load(); }
  std::size_t queued_keyframes() const;
  void interrupt_bundle_adjustment() { abort_ba_ = true; }

  // Synchronous mode: processes every queued keyframe now (no-op when threaded).
  void process_pending();
  // Waits until the queue is empty and the current keyframe is done.
  void flush();
  // Finishes the keyframe in progress, drops nothing queued (processes it), joins.
  void stop();
  // Loop correction: pause() lets the keyframe in progress finish (its BA is
  // interrupted), then keeps the worker from starting another one and returns
  // once it is idle; resume() lets it continue. Keyframes inserted meanwhile
  // queue up. No-ops in synchronous mode (the owner's thread is the worker).
  void pause();
  void resume();

  LocalMapperStats stats() const;

 private:
  void run();
  void process(const KeyFramePtr& kf);
  bool has_new_keyframes() const;

  Map& map_;
  LocalMapperOptions options_;
  mutable std::mutex queue_mutex_;
  std::condition_variable queue_changed_;
  std::deque<KeyFramePtr> queue_;
  bool busy_ = false;
  bool stopping_ = false;
  bool paused_ = false;
  std::atomic<bool> idle_{true};
  std::atomic<bool> abort_ba_{false};
  std::vector<MapPointPtr> recent_points_;
  mutable std::mutex stats_mutex_;
  LocalMapperStats stats_;
  std::thread thread_;  // last: starts after the members above exist
};

}  // namespace stillslam
