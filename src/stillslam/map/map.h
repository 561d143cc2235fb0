#pragma once
// The map: owns keyframes and map points (shared_ptr), hands out ids.
//
// Locking (one rule for the whole map): any code that reads or changes
// keyframes, map points or the covisibility graph holds update_mutex().
// Tracking holds it while it matches against the map and creates keyframes;
// local mapping holds it for each structural step and releases it while
// bundle adjustment optimizes on copies. The objects themselves carry no locks.
#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "stillslam/map/keyframe.h"
#include "stillslam/map/map_point.h"

namespace stillslam {

class Frame;

// Keyframe and map-point id counters. The maps of an Atlas share one, so ids
// are unique across maps (one keyframe database indexes them all). Atomic:
// maps are locked independently.
struct MapIdCounters {
  std::atomic<std::uint64_t> next_keyframe{0};
  std::atomic<std::uint64_t> next_point{0};
};

class Map {
 public:
  // A stand-alone map (id 0, its own id counters).
  Map();
  // A map of an Atlas: `id` names it, `ids` is shared with the other maps.
  Map(std::uint64_t id, std::shared_ptr<MapIdCounters> ids);

  std::uint64_t id() const { return id_; }
  const std::shared_ptr<MapIdCounters>& id_counters() const { return ids_; }
  std::mutex& update_mutex() const { return update_mutex_; }

  // Creates a keyframe from a posed frame and adds it (the caller still has to
  // add observations / connections). The map's first keyframe is its origin.
  KeyFramePtr create_keyframe(const Frame& frame);
  // Creates a point (not yet observed) and adds it.
  MapPointPtr create_map_point(const Eigen::Vector3d& position_world, KeyFrame* reference);

  // Culls a keyframe (KeyFrame::set_bad) and drops it from the active set; the
  // object stays alive so frames referencing it keep a pose.
  void erase_keyframe(const KeyFramePtr& kf);
  // Forgets points that turned bad (they stay alive while referenced).
  void remove_bad_points();

  // Adds existing objects (map merging, loading). A culled keyframe only
  // joins all_keyframes(). Ids must be unique (they come from the counters).
  void add_keyframe(const KeyFramePtr& kf);
  void add_map_point(const MapPointPtr& mp);
  // Moves every keyframe (also culled ones) and point of `other` into this
  // map; `other` is left empty. The caller holds both maps' mutexes.
  void absorb(Map& other);
  bool empty() const { return all_keyframes_.empty() && points_.empty(); }

  // Active keyframes / points, sorted by id.
  std::vector<KeyFramePtr> keyframes() const;
  std::vector<MapPointPtr> map_points() const;
  std::size_t num_keyframes() const { return keyframes_.size(); }
  std::size_t num_map_points() const;
  KeyFramePtr keyframe(std::uint64_t id) const;
  // Every keyframe ever created (also culled ones), by id.
  const std::vector<KeyFramePtr>& all_keyframes() const { return all_keyframes_; }

 private:
  mutable std::mutex update_mutex_;
  std::uint64_t id_ = 0;
  std::shared_ptr<MapIdCounters> ids_;
  std::map<std::uint64_t, KeyFramePtr> keyframes_;
  std::vector<KeyFramePtr> all_keyframes_;  // by creation (id) order
  std::map<std::uint64_t, MapPointPtr> points_;
};

}  // namespace stillslam
