#pragma once
// Builds keyframes of a SyntheticScene into a Map with exact data association
// (one map point per scene point), for map and mapping tests.
#include <map>

#include "map/synthetic_scene.h"
#include "stillslam/map/map.h"

namespace stillslam::test {

class MapBuilder {
 public:
  explicit MapBuilder(const SyntheticScene& scene) : scene_(scene) {}
  // Builds into map `map_id` sharing `ids` with other maps (an atlas' counters).
  MapBuilder(const SyntheticScene& scene, std::uint64_t map_id, std::shared_ptr<MapIdCounters> ids)
      : scene_(scene), map_(map_id, std::move(ids)) {}

  KeyFramePtr add_keyframe(const Eigen::Isometry3d& T_cam_world) {
    std::vector<std::size_t> ids;
    Frame frame = scene_.make_frame(next_frame_++, T_cam_world, &ids);
    frame.set_pose(T_cam_world);
    KeyFramePtr kf = map_.create_keyframe(frame);
    for (std::size_t i = 0; i < ids.size(); ++i) {
      MapPointPtr& mp = point_of_scene_[ids[i]];
      if (!mp) mp = map_.create_map_point(scene_.points()[ids[i]], kf.get());
      mp->add_observation(kf.get(), i);
      kf->set_map_point(i, mp);
    }
    for (const auto& mp : kf->map_points()) {
      if (mp) {
        mp->compute_distinctive_descriptor();
        mp->update_normal_and_depth(scene_.setup()->pyramid);
      }
    }
    kf->update_connections();
    return kf;
  }
  Map& map() { return map_; }
  const std::map<std::size_t, MapPointPtr>& points() const { return point_of_scene_; }

 private:
  const SyntheticScene& scene_;
  Map map_;
  std::map<std::size_t, MapPointPtr> point_of_scene_;
  std::uint64_t next_frame_ = 0;
};

}  // namespace stillslam::test
