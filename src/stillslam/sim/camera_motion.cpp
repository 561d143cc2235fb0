#include "stillslam/sim/camera_motion.h"

#include <algorithm>
#include <cmath>

#include "stillslam/core/error.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/sim/random.h"
#include "stillslam/sim/scene_layout.h"

namespace stillslam::sim {
namespace fs = std::filesystem;
namespace {

constexpr double kGeneratedStart = 1700000000.0;  // seconds; any TUM-like epoch

Eigen::Matrix3d cam_rot(double yaw, double pitch, double roll) {
  // Camera axes: yaw about y (down), pitch about x (right), roll about z (optical axis).
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

}  // namespace

Eigen::Isometry3d look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
  const Eigen::Vector3d z = (target - eye).normalized();
  Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ());
  if (x.norm() < 1e-9) x = Eigen::Vector3d::UnitX();
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = x;
  T.linear().col(1) = y;
  T.linear().col(2) = z;
  T.translation() = eye;
  return T;
}

CameraMotion CameraMotion::create(const std::string& name, const fs::path& data_dir,
                                  std::uint64_t seed) {
  CameraMotion m;
  SplitMix rng(seed * 7919 + 17);
  for (double& p : m.phase_) p = rng.uniform(0.0, kTwoPi);
  m.start_ns_ = static_cast<std::int64_t>(kGeneratedStart) * 1000000000LL;
  m.duration_ = 1e9;
  if (name == "halfsphere") {
    m.kind_ = Kind::HalfSphere;
  } else if (name == "rpy") {
    m.kind_ = Kind::Rpy;
  } else if (name == "static") {
    m.kind_ = Kind::Static;
  } else if (name == "loop") {
    m.kind_ = Kind::Loop;
  } else {
    const fs::path file =
        name == "walking_xyz" ? data_dir / "sim" / "tum_fr3_walking_xyz_groundtruth.txt" : fs::path(name);
    if (name != "walking_xyz" && !fs::exists(file)) {
      throw Error("--trajectory " + name +
                  ": not a file; use walking_xyz, halfsphere, rpy, static, loop or a TUM trajectory file");
    }
    m.kind_ = Kind::File;
    if (!fs::exists(file)) {
      throw Error("walking_xyz needs " + file.string() + " (TUM fr3/walking_xyz ground truth); pass --data-dir <repo>/data");
    }
    for (const StampedPose& p : read_trajectory(file)) {
      if (!m.keys_.empty() && p.timestamp <= m.keys_.back().t) {
        throw Error(file.string() + ": timestamps must increase");
      }
      m.keys_.push_back({p.timestamp, p.T_world_cam});
    }
    if (m.keys_.size() < 2) throw Error(file.string() + ": needs at least two poses");
    // Microsecond-rounded start keeps file names short and exact.
    m.start_ns_ = std::llround(m.keys_.front().t * 1e6) * 1000LL;
    m.duration_ = m.keys_.back().t - m.keys_.front().t;
  }
  return m;
}

Eigen::Isometry3d CameraMotion::pose_at(double dt) const {
  const double t = std::clamp(dt, 0.0, duration_);
  switch (kind_) {
    case Kind::File: {
      const double abs_t = keys_.front().t + t;
      auto it = std::upper_bound(keys_.begin(), keys_.end(), abs_t,
                                 [](double v, const TimedPose& p) { return v < p.t; });
      if (it == keys_.begin()) return keys_.front().T_world_cam;
      if (it == keys_.end()) return keys_.back().T_world_cam;
      const TimedPose& b = *it;
      const TimedPose& a = *(it - 1);
      const double s = (abs_t - a.t) / (b.t - a.t);
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.linear() = Eigen::Quaterniond(a.T_world_cam.linear())
                       .slerp(s, Eigen::Quaterniond(b.T_world_cam.linear()))
                       .toRotationMatrix();
      T.translation() = (1 - s) * a.T_world_cam.translation() + s * b.T_world_cam.translation();
      return T;
    }
    case Kind::HalfSphere: {
      // Like TUM fr3/walking_halfsphere: the camera is carried over a half
      // sphere of ~1 m diameter (centre 0.35 m in front of the origin, the
      // half facing away from the desk) while it looks at the desk area; the
      // aim point wanders over the desk so the camera also yaws and pitches.
      // ~0.2 m/s and up to ~25 deg/s, close to the real sequence.
      constexpr double kRadius = 0.5;
      const double az = 1.0 * std::sin(kTwoPi * t / 16.0 + phase_[0]);
      const double el = 0.5 * std::sin(kTwoPi * t / 11.0 + phase_[1]);
      const Eigen::Vector3d eye = Eigen::Vector3d(0, 0.35, 0) +
          kRadius * Eigen::Vector3d(std::sin(az) * std::cos(el), -std::cos(az) * std::cos(el), std::sin(el));
      const Eigen::Vector3d aim(0.35 * std::sin(kTwoPi * t / 13.0 + phase_[2]), SceneLayout::desk_centre().y(),
                                -0.35 + 0.15 * std::sin(kTwoPi * t / 9.0 + phase_[3]));
      return look_at(eye, aim);
    }
    case Kind::Rpy: {
      Eigen::Isometry3d T = look_at(Eigen::Vector3d::Zero(), SceneLayout::desk_centre());
      T.linear() = T.linear() * cam_rot(0.35 * std::sin(kTwoPi * t / 9.0 + phase_[0]),
                                        0.25 * std::sin(kTwoPi * t / 7.0 + phase_[1]),
                                        0.25 * std::sin(kTwoPi * t / 11.0 + phase_[2]));
      return T;
    }
    case Kind::Static: {
      // Hand-held "static": millimetres and a few tenths of a degree of jitter.
      Eigen::Isometry3d T = look_at(Eigen::Vector3d::Zero(), SceneLayout::desk_centre());
      Eigen::Vector3d d;
      for (int i = 0; i < 3; ++i) d[i] = 0.002 * std::sin(kTwoPi * (0.7 + 0.6 * i) * t + phase_[i]);
      T.translation() += d;
      T.linear() = T.linear() * cam_rot(0.003 * std::sin(kTwoPi * 0.9 * t + phase_[3]),
                                        0.003 * std::sin(kTwoPi * 1.3 * t + phase_[4]),
                                        0.002 * std::sin(kTwoPi * 1.7 * t + phase_[5]));
      return T;
    }
    case Kind::Loop: {
      // A walk around the room: the camera goes round a 0.5 m circle in the
      // free floor between the desk and the shelf, looking outward (desk,
      // right wall, shelf, side table, desk again), so every wall and piece of
      // furniture is 1-3 m away and in the depth range. Height and pitch
      // wobble with whole multiples of the turn's frequency: the path is
      // exactly periodic, so the start place is revisited with its start pose.
      const double w = kTwoPi / kLoopPeriod;
      const double heading = w * t;  // 0: looking along +y at the desk; turning right (clockwise from above)
      const Eigen::Vector3d out(std::sin(heading), std::cos(heading), 0.0);
      const Eigen::Vector3d centre(0.0, 0.6, 0.0);
      const double height = 0.08 * std::sin(2 * w * t + phase_[0]);
      const double pitch = -0.12 + 0.06 * std::sin(3 * w * t + phase_[1]);  // radians, negative = down
      const Eigen::Vector3d eye = centre + 0.5 * out + Eigen::Vector3d(0, 0, height);
      const Eigen::Vector3d target = eye + out * std::cos(pitch) + Eigen::Vector3d(0, 0, std::sin(pitch));
      return look_at(eye, target);
    }
  }
  return Eigen::Isometry3d::Identity();
}

}  // namespace stillslam::sim
