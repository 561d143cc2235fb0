#pragma once
// The ROS 2 messages stillslam reads from and writes to bags, as plain
// structs with the fields of their public interface definitions
// (std_msgs, sensor_msgs, geometry_msgs, nav_msgs, tf2_msgs). Poses keep
// ROS's quaternion order (x, y, z, w) in the structs; ros2_message_codec.h
// turns them into and from CDR.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace stillslam::ros2 {

struct Header {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
  std::string frame_id;
  std::int64_t stamp_ns() const { return static_cast<std::int64_t>(sec) * 1'000'000'000 + nanosec; }
  void set_stamp_ns(std::int64_t ns) {
    sec = static_cast<std::int32_t>(ns / 1'000'000'000);
    nanosec = static_cast<std::uint32_t>(ns % 1'000'000'000);
  }
};

struct Image {  // sensor_msgs/msg/Image
  Header header;
  std::uint32_t height = 0, width = 0;
  std::string encoding;
  std::uint8_t is_bigendian = 0;
  std::uint32_t step = 0;
  std::vector<std::uint8_t> data;
};

struct CompressedImage {  // sensor_msgs/msg/CompressedImage
  Header header;
  std::string format;  // "jpeg", "png", "16UC1; compressedDepth png", ...
  std::vector<std::uint8_t> data;
};

struct CameraInfo {  // sensor_msgs/msg/CameraInfo (binning and ROI are read and written as given)
  Header header;
  std::uint32_t height = 0, width = 0;
  std::string distortion_model;
  std::vector<double> d;
  std::array<double, 9> k{};
  std::array<double, 9> r{};
  std::array<double, 12> p{};
  std::uint32_t binning_x = 0, binning_y = 0;
  std::uint32_t roi_x_offset = 0, roi_y_offset = 0, roi_height = 0, roi_width = 0;
  bool roi_do_rectify = false;
};

struct Pose {  // geometry_msgs/msg/Pose (also Transform: translation + rotation)
  std::array<double, 3> position{};
  std::array<double, 4> orientation{0, 0, 0, 1};  // x, y, z, w
};

struct PoseStamped {  // geometry_msgs/msg/PoseStamped
  Header header;
  Pose pose;
};

struct Odometry {  // nav_msgs/msg/Odometry
  Header header;
  std::string child_frame_id;
  Pose pose;
  std::array<double, 36> pose_covariance{};
  std::array<double, 3> linear{}, angular{};
  std::array<double, 36> twist_covariance{};
};

struct TransformStamped {  // geometry_msgs/msg/TransformStamped
  Header header;  // frame_id: the parent frame
  std::string child_frame_id;
  Pose transform;  // child in parent
};

struct TfMessage {  // tf2_msgs/msg/TFMessage
  std::vector<TransformStamped> transforms;
};

}  // namespace stillslam::ros2
