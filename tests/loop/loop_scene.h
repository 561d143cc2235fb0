#pragma once
// A synthetic loop for loop-closing tests (no images): points with random
// descriptors on a cylinder wall around the origin, keyframes on a circle
// looking outward. The map is built as odometry would: keyframe i sits in a
// slowly drifting world W(angle) * truth, its new points are placed in that
// drifted world, and points are only re-observed by the next few keyframes,
// so when the circle comes back the old points are not re-associated (that
// is the loop closer's job). Keypoints and depths are exact projections of the
// true scene; the map (poses and points) drifts smoothly, so it is nearly
// consistent locally (a few pixels over the reuse window) and wrong globally.
#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <vector>

#include "cylinder_world.h"  // same folder: benches include these headers too

namespace stillslam::test {

class LoopScene {
 public:
  struct Options {
    int num_points = 3000;
    double wall_radius = 5.0;
    double camera_radius = 1.0;
    double step_deg = 10.0;
    int reuse_window = 6;          // a point is re-observed by this many later keyframes
    double drift_yaw_deg = 8.0;    // per full turn
    double drift_translation = 0.05;  // metres per full turn (sum of the per-step biases)
    std::uint32_t seed = 5;
  };

  explicit LoopScene(Options options)
      : options_(options), world_(options.num_points, options.wall_radius, options.seed) {}
  LoopScene() : LoopScene(Options{}) {}

  const std::shared_ptr<CameraSetup>& setup() const { return world_.setup(); }
  double angle_of(int i) const { return options_.step_deg * i * M_PI / 180.0; }

  Eigen::Isometry3d true_T_world_cam(int i) const {
    const double a = angle_of(i);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix();
    T.translation() = options_.camera_radius * Eigen::Vector3d(std::sin(a), 0, std::cos(a));
    return T;
  }
  // The drift of the world at keyframe i (identity at i = 0): odometry with a
  // constant bias E per step (in the camera frame, as visual odometry drifts),
  // T_world_cam_drifted(i) = T_world_cam_drifted(i - 1) * T_true(i-1, i) * E.
  Eigen::Isometry3d drift(int i) const {
    const double steps_per_turn = 360.0 / options_.step_deg;
    Eigen::Isometry3d E = Eigen::Isometry3d::Identity();
    E.linear() = Eigen::AngleAxisd(options_.drift_yaw_deg / steps_per_turn * M_PI / 180.0, Eigen::Vector3d::UnitY())
                     .toRotationMatrix();
    E.translation() = options_.drift_translation / steps_per_turn * Eigen::Vector3d(1.0, 0.1, 0.5).normalized();
    Eigen::Isometry3d T_drifted = true_T_world_cam(0);
    for (int k = 1; k <= i; ++k) {
      T_drifted = T_drifted * (true_T_world_cam(k - 1).inverse() * true_T_world_cam(k)) * E;
    }
    return T_drifted * true_T_world_cam(i).inverse();
  }

  // A frame with exact measurements from a true pose (no pose set): for
  // relocalization queries.
  Frame make_frame(std::uint64_t id, const Eigen::Isometry3d& T_world_cam_true) const {
    return world_.make_frame(id, T_world_cam_true);
  }

  // Adds keyframe i (call with i = 0, 1, 2, ... in order).
  KeyFramePtr add_keyframe(int i) {
    return world_.add_keyframe(map_, static_cast<std::uint64_t>(i), true_T_world_cam(i), drift(i), live_, i,
                               options_.reuse_window);
  }

  Map& map() { return map_; }

  Vocabulary train_vocabulary() const { return world_.train_vocabulary(); }

  // Largest camera-centre error of the map's keyframes against the truth.
  double max_position_error() const {
    double e = 0;
    for (const auto& kf : map_.keyframes()) {
      const int i = static_cast<int>(kf->id());
      e = std::max(e, (kf->camera_center() - true_T_world_cam(i).translation()).norm());
    }
    return e;
  }
  double max_rotation_error_deg() const {
    double e = 0;
    for (const auto& kf : map_.keyframes()) {
      const int i = static_cast<int>(kf->id());
      const Eigen::Matrix3d dR = kf->T_world_cam().linear().transpose() * true_T_world_cam(i).linear();
      e = std::max(e, Eigen::AngleAxisd(dR).angle() * 180.0 / M_PI);
    }
    return e;
  }

 private:
  Options options_;
  CylinderWorld world_;
  Map map_;
  CylinderWorld::LivePoints live_;
};

}  // namespace stillslam::test
