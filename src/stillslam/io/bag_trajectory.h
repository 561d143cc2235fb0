#pragma once
// A trajectory from a bag topic, for `stillslam bag-export` and `eval`:
// nav_msgs/Odometry, geometry_msgs/PoseStamped and PoseWithCovarianceStamped
// give the pose of each message; tf2_msgs/TFMessage gives the transforms of one named frame pair
// (PARENT -> CHILD, the child's pose in the parent; chains of frames are
// not composed). Stamps are the header stamps, sorted; a repeated stamp
// keeps the first pose.
#include <optional>
#include <string>
#include <utility>

#include "stillslam/core/trajectory.h"
#include "stillslam/io/bag_reader.h"

namespace stillslam {

struct BagTrajectoryOptions {
  std::string topic;
  std::optional<std::pair<std::string, std::string>> frames;  // TF: parent, child (required for TF)
};

// Error naming the topic and listing the bag's pose topics (or, for TF, the
// frame pairs it holds) when there is nothing to export.
Trajectory read_bag_trajectory(const BagReader& bag, const BagTrajectoryOptions& options);

}  // namespace stillslam
