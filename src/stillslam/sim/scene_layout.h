#pragma once
// The static office-like room every sequence is shot in, built in the scene
// frame: z up, floor at z = -1.4 (camera height ~1.4 m), the camera's mean
// position at the origin looking along +y. Surfaces lie 1-4 m from the camera
// like in the TUM fr3 office. Every surface is tiled with photo panels so ORB
// finds corners wherever the camera looks.
#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "stillslam/sim/camera_motion.h"
#include "stillslam/sim/quad.h"
#include "stillslam/sim/random.h"

namespace stillslam::sim {

struct SceneLayout {
  static constexpr double kFloorZ = -1.4, kCeilingZ = 1.3;
  static constexpr double kMinX = -2.6, kMaxX = 2.6, kMinY = -2.2, kMaxY = 3.8;
  static constexpr double kDeskTopZ = -0.65;
  static Eigen::Vector3d desk_centre() { return {0.0, 1.9, kDeskTopZ}; }
  // Floor point at the front edge of chair i (0 or 1) behind the desk, where a
  // seated person's billboard stands.
  static Eigen::Vector3d chair_front(int i) { return {i == 0 ? -1.25 : 1.0, 2.5, kFloorZ}; }
  // Furniture standing on the floor (the boxes build_static_scene draws):
  // where nobody may walk, and (when tall) what hides people behind it.
  static Eigen::AlignedBox3d desk() { return box({-0.8, 1.5, kFloorZ}, {0.8, 2.3, kDeskTopZ}); }
  static Eigen::AlignedBox3d side_table() { return box({-2.5, 0.4, kFloorZ}, {-1.8, 2.4, -0.7}); }
  static Eigen::AlignedBox3d cabinet() { return box({1.3, 3.2, kFloorZ}, {2.5, 3.78, 0.4}); }
  static Eigen::AlignedBox3d shelf() { return box({-1.0, -2.18, kFloorZ}, {1.0, -1.8, 0.6}); }
  // Seat and backrest of chair i together.
  static Eigen::AlignedBox3d chair(int i) {
    const Eigen::Vector3d c = chair_front(i);
    return box({c.x() - 0.23, c.y() + 0.02, kFloorZ}, {c.x() + 0.23, c.y() + 0.47, kFloorZ + 0.95});
  }
  static std::vector<Eigen::AlignedBox3d> furniture() {
    return {desk(), side_table(), cabinet(), shelf(), chair(0), chair(1)};
  }

 private:
  static Eigen::AlignedBox3d box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    return Eigen::AlignedBox3d(lo, hi);
  }
};

// Where the scene frame sits in the trajectory's world frame. Generated paths
// live in the scene frame (identity). Replayed files: origin at the mean camera
// position over the first `seconds` of the path, up = minus the mean camera
// y axis (image down), forward = the mean optical axis made horizontal.
Eigen::Isometry3d scene_frame_for(const CameraMotion& motion, double seconds);

// Photo panels picked from `texture_sizes` (index = texture id) by `seed`.
// movable_chair: when given, chair 1 goes there (scene frame) instead of into
// the static scene, for DynamicObjects to move; the other panels are the same
// either way (the same random draws are made).
std::vector<Quad> build_static_scene(const Eigen::Isometry3d& T_world_scene,
                                     const std::vector<cv::Size>& texture_sizes, std::uint64_t seed,
                                     std::vector<Quad>* movable_chair = nullptr);

// Helpers shared with the dynamic objects.
class PanelPainter {
 public:
  PanelPainter(const std::vector<cv::Size>& texture_sizes, std::uint64_t seed);
  // A quad with a random texture crop whose aspect matches the panel (no stretching).
  Quad panel(const Eigen::Vector3d& origin, const Eigen::Vector3d& axis_u,
             const Eigen::Vector3d& axis_v, float brightness_min = 0.85f,
             float brightness_max = 1.05f);
  // The five visible faces (no bottom) of an axis-aligned box.
  void box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::vector<Quad>& out);
  double uniform(double a, double b);

 private:
  std::vector<cv::Size> sizes_;
  SplitMix rng_;
};

}  // namespace stillslam::sim
