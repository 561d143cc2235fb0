#include "pose_messages.h"

#include "ros_time.h"
#include "stillslam/core/error.h"

namespace stillslam::ros2 {

namespace {

// The C structs take char*; dds_write only reads it.
char* borrow(const std::string& s) { return const_cast<char*>(s.c_str()); }

}  // namespace

geometry_msgs_msg_dds__Pose_ pose_message(const Eigen::Isometry3d& T_map_cam) {
  const Eigen::Vector3d t = T_map_cam.translation();
  const Eigen::Quaterniond q(T_map_cam.rotation());
  return {{t.x(), t.y(), t.z()}, {q.x(), q.y(), q.z(), q.w()}};
}

Eigen::Isometry3d pose_from_message(const geometry_msgs_msg_dds__Pose_& pose) {
  const auto& o = pose.orientation;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(o.w, o.x, o.y, o.z).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return T;
}

geometry_msgs_msg_dds__PoseStamped_ pose_stamped(const Eigen::Isometry3d& T_map_cam, std::int64_t stamp_ns,
                                                  const std::string& map_frame) {
  geometry_msgs_msg_dds__PoseStamped_ m{};
  m.header.stamp = stamp_from_nanoseconds(stamp_ns);
  m.header.frame_id = borrow(map_frame);
  m.pose = pose_message(T_map_cam);
  return m;
}

TfMessage::TfMessage(const Eigen::Isometry3d& T_map_cam, std::int64_t stamp_ns, const std::string& map_frame,
                     const std::string& camera_frame) {
  transform_.header.stamp = stamp_from_nanoseconds(stamp_ns);
  transform_.header.frame_id = borrow(map_frame);
  transform_.child_frame_id = borrow(camera_frame);
  const geometry_msgs_msg_dds__Pose_ p = pose_message(T_map_cam);
  transform_.transform.translation = {p.position.x, p.position.y, p.position.z};
  transform_.transform.rotation = p.orientation;
  message_.transforms._maximum = message_.transforms._length = 1;
  message_.transforms._buffer = &transform_;
  message_.transforms._release = false;
}

PathMessage::PathMessage(std::string map_frame, std::size_t max_poses)
    : map_frame_(std::move(map_frame)), max_poses_(max_poses) {
  if (max_poses_ == 0) throw Error("the path needs room for at least one pose (--path-max-poses >= 1)");
}

void PathMessage::add(const Eigen::Isometry3d& T_map_cam, std::int64_t stamp_ns) {
  if (poses_.size() == max_poses_) poses_.erase(poses_.begin());
  poses_.push_back(pose_stamped(T_map_cam, stamp_ns, map_frame_));
}

const nav_msgs_msg_dds__Path_& PathMessage::message(std::int64_t stamp_ns) {
  message_.header.stamp = stamp_from_nanoseconds(stamp_ns);
  message_.header.frame_id = borrow(map_frame_);
  message_.poses._maximum = message_.poses._length = static_cast<std::uint32_t>(poses_.size());
  message_.poses._buffer = poses_.data();
  message_.poses._release = false;
  return message_;
}

}  // namespace stillslam::ros2
