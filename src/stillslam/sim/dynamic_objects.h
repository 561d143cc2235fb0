#pragma once
// Everything that moves: people (RGBA billboards at human height, always
// facing the camera, walking back and forth across the view with a little
// bob and sway), people who stay still (seated on the chairs behind the desk,
// swaying slightly), and a box carried across the desk. Each gets its own
// Quad::dynamic_id so masks can be told apart; the box is marked dynamic only
// while it moves (before and after it is part of the static scene).
#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "stillslam/sim/quad.h"
#include "stillslam/sim/scene_layout.h"

namespace stillslam::sim {

struct PersonTrack {
  int texture = 0;               // renderer texture index of the cut-out
  double height = 1.7;           // metres
  double aspect = 0.4;           // cut-out width / height
  Eigen::Vector2d a, b;          // walking between these floor points (scene frame)
  double speed = 1.0;            // m/s
  double pause = 2.0;            // seconds out of view at each end
  double stop_at = 0.5;          // fraction of the path where the person stands a while
  double stop_time = 0.0;        // seconds standing there (0 = walks straight through)
  double offset = 0.0;           // seconds into the back-and-forth cycle at t = 0
  bool still = false;            // stands at `a`, only sways
  std::uint16_t id = 1;
};

struct DynamicObjectsOptions {
  int walking = 2;
  int still = 0;
  bool moved_box = false;
  double duration = 10.0;        // seconds; the box moves at 40% of it
};

class DynamicObjects {
 public:
  // cutout_textures: renderer texture indices of the cut-outs; cutout_sizes: their pixel sizes.
  // sitting_*: the same for seated people (may be empty: still people then stand).
  DynamicObjects(const DynamicObjectsOptions& options, const Eigen::Isometry3d& T_world_scene,
                 const std::vector<int>& cutout_textures, const std::vector<cv::Size>& cutout_sizes,
                 const std::vector<int>& sitting_textures, const std::vector<cv::Size>& sitting_sizes,
                 const std::vector<cv::Size>& texture_sizes, std::uint64_t seed);

  // Quads at time t (seconds since the start); billboards face camera_world.
  std::vector<Quad> quads_at(double t, const Eigen::Vector3d& camera_world) const;
  const std::vector<PersonTrack>& people() const { return people_; }

 private:
  Eigen::Vector3d person_foot(const PersonTrack& p, double t) const;  // scene frame

  DynamicObjectsOptions options_;
  Eigen::Isometry3d T_world_scene_;
  std::vector<PersonTrack> people_;
  std::vector<Quad> box_;        // the movable box in scene frame at its start, resting
  std::uint16_t box_id_ = 0;
};

}  // namespace stillslam::sim
