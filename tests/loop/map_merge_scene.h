#pragma once
// Two maps of one synthetic scene for map-merging tests (no images): points
// with random descriptors on a cylinder wall, keyframes on a circle looking
// outward, exact measurements. Each map is built as tracking would from its
// own first keyframe: map B's world frame is unknown to map A (an arbitrary
// rigid transform), points are re-observed by the next few keyframes of the
// same map only. Both maps share one set of id counters (as in an Atlas).
#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "cylinder_world.h"  // same folder: benches include these headers too

namespace stillslam::test {

class MapMergeScene {
 public:
  explicit MapMergeScene(std::uint32_t seed = 7, int num_points = 3000) : world_(num_points, 5.0, seed) {}

  const std::shared_ptr<CameraSetup>& setup() const { return world_.setup(); }
  const Eigen::Vector3d& point(std::size_t s) const { return world_.point(s); }

  // The true camera pose at `deg` degrees on the circle (radius 1 m).
  static Eigen::Isometry3d true_T_world_cam(double deg) {
    const double a = deg * M_PI / 180.0;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(std::sin(a), 0, std::cos(a));
    return T;
  }

  // One map under construction: its frame is T_map_world * (true world).
  struct MapBuild {
    Map* map = nullptr;
    Eigen::Isometry3d T_map_world = Eigen::Isometry3d::Identity();
    int reuse_window = 6;
    int count = 0;
    CylinderWorld::LivePoints live;
    std::map<std::uint64_t, double> degrees;  // keyframe id -> true angle
  };

  // Adds a keyframe at `deg` to the map (exact measurements, pose in the map's frame).
  KeyFramePtr add_keyframe(MapBuild& b, double deg) {
    KeyFramePtr kf = world_.add_keyframe(*b.map, next_frame_id_++, true_T_world_cam(deg), b.T_map_world, b.live,
                                         b.count, b.reuse_window);
    b.degrees[kf->id()] = deg;
    ++b.count;
    return kf;
  }

  Vocabulary train_vocabulary() const { return world_.train_vocabulary(); }

 private:
  CylinderWorld world_;
  std::uint64_t next_frame_id_ = 0;
};

}  // namespace stillslam::test
