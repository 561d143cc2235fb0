#pragma once
// CDR encoding and decoding of the messages in ros2_messages.h. decode_*
// throws Error naming `what` (topic and message) on a short or corrupt
// payload; encode_* writes little-endian CDR.
#include <cstdint>
#include <string>
#include <vector>

#include "stillslam/io/ros2_messages.h"

namespace stillslam::ros2 {

using Bytes = std::vector<std::uint8_t>;

Image decode_image(const Bytes& cdr, const std::string& what);
CompressedImage decode_compressed_image(const Bytes& cdr, const std::string& what);
CameraInfo decode_camera_info(const Bytes& cdr, const std::string& what);
PoseStamped decode_pose_stamped(const Bytes& cdr, const std::string& what);
Odometry decode_odometry(const Bytes& cdr, const std::string& what);
TfMessage decode_tf_message(const Bytes& cdr, const std::string& what);
// Only the header (every stamped message starts with it).
Header decode_header(const Bytes& cdr, const std::string& what);
// Only the header's stamp (the first 12 bytes with the encapsulation), in ns.
std::int64_t decode_stamp_ns(const Bytes& cdr, const std::string& what);

Bytes encode(const Image& m);
Bytes encode(const CompressedImage& m);
Bytes encode(const CameraInfo& m);
Bytes encode(const PoseStamped& m);
Bytes encode(const Odometry& m);
Bytes encode(const TfMessage& m);

// ROS 2 type names, e.g. "sensor_msgs/msg/Image".
inline constexpr const char* kImageType = "sensor_msgs/msg/Image";
inline constexpr const char* kCompressedImageType = "sensor_msgs/msg/CompressedImage";
inline constexpr const char* kCameraInfoType = "sensor_msgs/msg/CameraInfo";
inline constexpr const char* kPoseStampedType = "geometry_msgs/msg/PoseStamped";
// Header + Pose first, as PoseStamped: decode_pose_stamped reads it (covariance ignored).
inline constexpr const char* kPoseWithCovarianceStampedType = "geometry_msgs/msg/PoseWithCovarianceStamped";
inline constexpr const char* kOdometryType = "nav_msgs/msg/Odometry";
inline constexpr const char* kTfMessageType = "tf2_msgs/msg/TFMessage";

}  // namespace stillslam::ros2
