#pragma once
// sensor_msgs/CameraInfo for a rectified pinhole camera (what ros2-replay
// publishes beside its images: no distortion, identity R, P with the
// baseline in P[3] = -fx * baseline for the right camera), and the node's
// check of a received one against its settings.
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "sensor_msgs/msg/CameraInfo.h"
#include "stillslam/geometry/camera_calibration.h"

namespace stillslam::ros2 {

class OutgoingCameraInfo {
 public:
  // baseline: metres for the right camera of a stereo pair, 0 otherwise.
  OutgoingCameraInfo(const CameraCalibration& camera, double baseline, std::int64_t stamp_ns,
                     const std::string& frame_id);
  OutgoingCameraInfo(const OutgoingCameraInfo&) = delete;
  OutgoingCameraInfo& operator=(const OutgoingCameraInfo&) = delete;
  const sensor_msgs_msg_dds__CameraInfo_& message() const { return message_; }

 private:
  std::string frame_id_, model_ = "plumb_bob";
  std::array<double, 5> d_{};
  sensor_msgs_msg_dds__CameraInfo_ message_{};
};

// Why a received CameraInfo does not describe `camera` (size, or fx fy cx
// cy of its projection P off by more than 1 %); nullopt when it does.
std::optional<std::string> camera_info_mismatch(const sensor_msgs_msg_dds__CameraInfo_& info,
                                                const CameraCalibration& camera);

}  // namespace stillslam::ros2
