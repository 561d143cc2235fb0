#pragma once
// The map: owns keyframes and map points (shared_ptr), hands out ids.
//
// Locking (one rule for the whole map): any code that reads or changes
// keyframes, map points or the covisibility graph holds update_mutex().
// Tracking holds it while it matches against the map and creates keyframes;
// local mapping holds it for each structural step and releases it while
// bundle adjustment optimizes on copies. The objects themselves carry no locks.
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "stillslam/map/keyframe.h"
#include "stillslam/map/map_point.h"

namespace stillslam {

class Frame;

class Map {
 public:
  std::mutex& update_mutex() const { return update_mutex_; }

  // Creates a keyframe from a posed frame and adds it (the caller still has to
  // add observations / connections).
  KeyFramePtr create_keyframe(const Frame& frame);
  // Creates a point (not yet observed) and adds it.
  MapPointPtr create_map_point(const Eigen::Vector3d& position_world, KeyFrame* reference);

  // Culls a keyframe (KeyFrame::set_bad) and drops it from the active set; the
  // object stays alive so frames referencing it keep a pose.
  void erase_keyframe(const KeyFramePtr& kf);
  // Forgets points that turned bad (they stay alive while referenced).
  void remove_bad_points();

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
  std::map<std::uint64_t, KeyFramePtr> keyframes_;
  std::vector<KeyFramePtr> all_keyframes_;
  std::map<std::uint64_t, MapPointPtr> points_;
  std::uint64_t next_keyframe_id_ = 0;
  std::uint64_t next_point_id_ = 0;
};

}  // namespace stillslam
