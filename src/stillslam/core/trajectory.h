#pragma once
// A camera trajectory: poses of the camera in the world, stamped in seconds.
// Reading and writing its file formats is io/trajectory.h.
#include <Eigen/Geometry>
#include <vector>

namespace stillslam {

struct StampedPose {
  double timestamp = 0;  // seconds
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();
};

using Trajectory = std::vector<StampedPose>;

}  // namespace stillslam
