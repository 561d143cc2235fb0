#pragma once
// The node's pose outputs as ROS 2 messages: geometry_msgs/PoseStamped (the
// camera in the map frame), tf2_msgs/TFMessage (map -> camera) and
// nav_msgs/Path. Frame names are borrowed from the caller's strings, which
// must outlive the write.
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry_msgs/msg/PoseStamped.h"
#include "geometry_msgs/msg/TransformStamped.h"
#include "nav_msgs/msg/Path.h"
#include "tf2_msgs/msg/TFMessage.h"

namespace stillslam::ros2 {

geometry_msgs_msg_dds__Pose_ pose_message(const Eigen::Isometry3d& T_map_cam);
Eigen::Isometry3d pose_from_message(const geometry_msgs_msg_dds__Pose_& pose);

geometry_msgs_msg_dds__PoseStamped_ pose_stamped(const Eigen::Isometry3d& T_map_cam, std::int64_t stamp_ns,
                                                  const std::string& map_frame);

// One transform, parent `map_frame`, child `camera_frame`.
class TfMessage {
 public:
  TfMessage(const Eigen::Isometry3d& T_map_cam, std::int64_t stamp_ns, const std::string& map_frame,
            const std::string& camera_frame);
  TfMessage(const TfMessage&) = delete;
  TfMessage& operator=(const TfMessage&) = delete;
  const tf2_msgs_msg_dds__TFMessage_& message() const { return message_; }

 private:
  geometry_msgs_msg_dds__TransformStamped_ transform_{};
  tf2_msgs_msg_dds__TFMessage_ message_{};
};

// The camera path: the poses published so far, the newest `max_poses`.
class PathMessage {
 public:
  PathMessage(std::string map_frame, std::size_t max_poses);
  PathMessage(const PathMessage&) = delete;
  PathMessage& operator=(const PathMessage&) = delete;
  void add(const Eigen::Isometry3d& T_map_cam, std::int64_t stamp_ns);
  void clear() { poses_.clear(); }  // a new map: its poses are in another frame
  std::size_t size() const { return poses_.size(); }
  // Valid until the next add() or clear().
  const nav_msgs_msg_dds__Path_& message(std::int64_t stamp_ns);

 private:
  std::string map_frame_;
  std::size_t max_poses_;
  std::vector<geometry_msgs_msg_dds__PoseStamped_> poses_;
  nav_msgs_msg_dds__Path_ message_{};
};

}  // namespace stillslam::ros2
