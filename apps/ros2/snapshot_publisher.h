#pragma once
// Sends the System's frame snapshots (publish layer) on ROS 2 topics from
// its own thread: geometry_msgs/PoseStamped and the map -> camera TF for
// tracked frames, nav_msgs/Path of the poses sent in the current map,
// std_msgs/String with the tracking state for every frame, and the dynamic
// mask as a mono8 image when segmentation made one. A snapshot newer than
// the one being sent replaces older ones (latest value): readers get the
// newest state, never a backlog.
#include <atomic>
#include <cstddef>
#include <memory>
#include <string>
#include <thread>

#include "dds.h"
#include "frame_stamps.h"
#include "geometry_msgs/msg/PoseStamped.h"
#include "nav_msgs/msg/Path.h"
#include "pose_messages.h"
#include "sensor_msgs/msg/Image.h"
#include "std_msgs/msg/String.h"
#include "stillslam/publish/publisher.h"
#include "tf2_msgs/msg/TFMessage.h"

namespace stillslam::ros2 {

struct NodeTopics;

class SnapshotPublisher {
 public:
  // `stamps`: the input stamps of the frames, for the outputs' headers.
  SnapshotPublisher(const DdsParticipant& participant, const Publisher& source, const FrameStamps& stamps,
                    const NodeTopics& topics, std::string map_frame, std::string camera_frame, std::size_t path_max_poses);
  ~SnapshotPublisher();  // stop()
  SnapshotPublisher(const SnapshotPublisher&) = delete;
  SnapshotPublisher& operator=(const SnapshotPublisher&) = delete;
  // Sends the newest snapshot if it was not sent yet, then ends the thread.
  void stop();
  std::size_t published_poses() const { return published_poses_; }

 private:
  void loop();
  void send(const FrameSnapshot& frame);

  const Publisher& source_;
  const FrameStamps& stamps_;
  std::string map_frame_, camera_frame_;
  DdsWriter<geometry_msgs_msg_dds__PoseStamped_> pose_;
  DdsWriter<nav_msgs_msg_dds__Path_> path_;
  DdsWriter<tf2_msgs_msg_dds__TFMessage_> tf_;
  DdsWriter<std_msgs_msg_dds__String_> state_;
  DdsWriter<sensor_msgs_msg_dds__Image_> mask_;
  PathMessage path_message_;
  std::uint64_t path_map_id_ = 0;
  std::uint64_t sent_version_ = 0;
  std::atomic<std::size_t> published_poses_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace stillslam::ros2
