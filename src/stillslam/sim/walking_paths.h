#pragma once
// Where walking people go: straight floor paths laid across the camera's line
// of sight at some time, so that a person walking them enters the view, crosses
// in front of the camera and leaves it again, whatever the camera path is
// (replayed file, halfsphere around the desk, rpy, ...). A path never runs
// through furniture or walls, never comes close to the camera anywhere along
// its path, and is not hidden behind tall furniture where it crosses the view.
// Everything here is in the scene frame (z up, see scene_layout.h).
#include <Eigen/Geometry>
#include <optional>
#include <vector>

namespace stillslam::sim {

struct CameraSample {
  double t = 0;                                           // seconds since the start
  Eigen::Vector3d position = Eigen::Vector3d::Zero();     // scene frame
  Eigen::Vector3d optical_axis = Eigen::Vector3d::UnitY();
};

struct WalkingPath {
  Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();  // floor points
  double crossing = 0.5;   // fraction of a -> b where the line of sight crosses the path
  double distance = 0;     // metres from the camera to the crossing (horizontally)
  double anchor_time = 0;  // when the camera looked along that line of sight
};

struct WalkingPathOptions {
  double min_distance = 0.6, max_distance = 3.3;  // crossing distance in front of the camera
  double body_radius = 0.08;    // clearance from furniture
  double wall_clearance = 0.25;
  double camera_clearance = 0.6;  // no path point this close to any camera position
  double half_view_tan = 0.6;     // tan of the horizontal half field of view
  // Furniture at least this tall (scene z of its top) hides a person behind it.
  double hiding_top_z = -0.2;
};

class WalkingPathPlanner {
 public:
  // samples: the camera path, in time order, every ~0.1 s over the sequence.
  WalkingPathPlanner(std::vector<CameraSample> samples, WalkingPathOptions options = {});

  // A path crossing the line of sight the camera has at time t (averaged over
  // +-1 s) as close as possible to `preferred_distance` metres in front of it,
  // long enough to leave the view on both sides where the room allows.
  // nullopt when no free crossing exists at that time.
  std::optional<WalkingPath> plan(double t, double preferred_distance) const;
  // As plan(), trying times ever farther from t until one works.
  std::optional<WalkingPath> plan_near(double t, double preferred_distance) const;

  // The floor point is free for a person (inside the room, outside furniture).
  bool free(const Eigen::Vector2d& p) const;
  // Smallest horizontal distance from the segment a-b to any camera position.
  double camera_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;
  const std::vector<CameraSample>& samples() const { return samples_; }

 private:
  double free_run(const Eigen::Vector2d& p, const Eigen::Vector2d& dir, double cap) const;
  bool hidden(const Eigen::Vector2d& from, const Eigen::Vector2d& to) const;

  std::vector<CameraSample> samples_;
  WalkingPathOptions options_;
  std::vector<Eigen::AlignedBox2d> obstacles_, tall_;
};

}  // namespace stillslam::sim
