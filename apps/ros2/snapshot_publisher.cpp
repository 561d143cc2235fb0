#include "snapshot_publisher.h"

#include <spdlog/spdlog.h>

#include <utility>
#include <vector>

#include "image_message.h"
#include "live_node.h"
#include "ros_time.h"
#include "stillslam/core/error.h"

namespace stillslam::ros2 {

SnapshotPublisher::SnapshotPublisher(const DdsParticipant& participant, const Publisher& source,
                                     const FrameStamps& stamps, const NodeTopics& topics, std::string map_frame, std::string camera_frame,
                                     std::size_t path_max_poses)
    : source_(source),
      stamps_(stamps),
      map_frame_(std::move(map_frame)),
      camera_frame_(std::move(camera_frame)),
      pose_(participant, geometry_msgs_msg_dds__PoseStamped__desc, topics.pose),
      path_(participant, nav_msgs_msg_dds__Path__desc, topics.path),
      tf_(participant, tf2_msgs_msg_dds__TFMessage__desc, topics.tf),
      state_(participant, std_msgs_msg_dds__String__desc, topics.state),
      mask_(participant, sensor_msgs_msg_dds__Image__desc, topics.mask),
      path_message_(map_frame_, path_max_poses),
      thread_([this] { loop(); }) {}

SnapshotPublisher::~SnapshotPublisher() { stop(); }

void SnapshotPublisher::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void SnapshotPublisher::loop() {
  for (;;) {
    const bool last = stop_;  // read before the snapshot: the final one is not missed
    const Publisher::FrameRead read = source_.wait_frame(sent_version_, std::chrono::milliseconds(last ? 0 : 100));
    if (read.value && read.version > sent_version_) {
      sent_version_ = read.version;
      try {
        send(*read.value);
      } catch (const Error& e) {
        spdlog::warn("ros2: {}", e.what());  // a lost output message must not stop tracking
      }
    }
    if (last) return;
  }
}

void SnapshotPublisher::send(const FrameSnapshot& frame) {
  const std::int64_t stamp = stamps_.stamp_ns(frame.index, frame.timestamp);
  std_msgs_msg_dds__String_ state{const_cast<char*>(frame.state.c_str())};
  // The frames the map's start waited on (sent without a pose) get theirs
  // first, each with its own stamp, then this frame.
  std::vector<std::pair<Eigen::Isometry3d, std::int64_t>> posed;
  for (const FrameSnapshot::EarlierPose& p : frame.start_frames_posed) {
    posed.emplace_back(p.T_world_cam, stamps_.stamp_ns(p.index, p.timestamp));
  }
  if (frame.has_pose) posed.emplace_back(frame.T_world_cam, stamp);
  for (const auto& [T_world_cam, pose_stamp] : posed) {
    pose_.write(pose_stamped(T_world_cam, pose_stamp, map_frame_));
    const TfMessage tf(T_world_cam, pose_stamp, map_frame_, camera_frame_);
    tf_.write(tf.message());
    if (frame.map_id != path_map_id_) {
      path_message_.clear();
      path_map_id_ = frame.map_id;
    }
    path_message_.add(T_world_cam, pose_stamp);
    ++published_poses_;
  }
  if (!posed.empty()) path_.write(path_message_.message(stamp));
  if (!frame.dynamic_mask.empty()) {
    const OutgoingImage mask(mask_image(frame.dynamic_mask), stamp, camera_frame_);
    mask_.write(mask.message());
  }
  // Last: a reader that waits for the state of a frame has its pose by then.
  state_.write(state);
}

}  // namespace stillslam::ros2
