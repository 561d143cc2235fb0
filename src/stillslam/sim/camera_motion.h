#pragma once
// The camera path of a sequence as a continuous function of time (so motion
// blur can sample poses inside one exposure). Generated paths are expressed in
// the scene frame (z up, camera around the origin looking along +y); replayed
// TUM files keep their own world frame and the scene is placed around them.
#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace stillslam::sim {

struct TimedPose {
  double t = 0;
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();
};

class CameraMotion {
 public:
  // name: walking_xyz | halfsphere | rpy | static | loop | <trajectory file: TUM, EuRoC or KITTI>. walking_xyz is
  // read from data_dir/sim/tum_fr3_walking_xyz_groundtruth.txt. seed varies phases of generated paths.
  // loop: one turn around the room every kLoopPeriod seconds (see pose_at), periodic, so frame
  // kLoopPeriod * fps repeats frame 0 exactly and later frames revisit the start.
  static CameraMotion create(const std::string& name, const std::filesystem::path& data_dir,
                             std::uint64_t seed);

  std::int64_t start_ns() const { return start_ns_; }  // timestamp of frame 0
  double duration() const { return duration_; }        // seconds of path available
  bool replayed() const { return !keys_.empty(); }
  // Pose at dt seconds after the start (clamped to the path).
  Eigen::Isometry3d pose_at(double dt) const;

  static constexpr double kLoopPeriod = 20.0;  // seconds per turn of the "loop" path

 private:
  enum class Kind { File, HalfSphere, Rpy, Static, Loop };
  Kind kind_ = Kind::Static;
  std::vector<TimedPose> keys_;
  std::int64_t start_ns_ = 0;
  double duration_ = 0;
  double phase_[6] = {0, 0, 0, 0, 0, 0};
};

// Camera looking from eye at target, with scene up = +z (x right, y down, z forward).
Eigen::Isometry3d look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target);

}  // namespace stillslam::sim
