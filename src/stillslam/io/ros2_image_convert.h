#pragma once
// sensor_msgs Image / CompressedImage <-> cv::Mat.
// Decoded images come out as 8UC1 (mono8), 8UC3 BGR (rgb8, bgr8, bgra8,
// rgba8, jpeg, png), 16UC1 (16UC1 / mono16: depth in millimetres, the ROS
// convention) or 32FC1 (depth in metres); rows honour `step` (padding) and
// `is_bigendian`. compressedDepth ("16UC1; compressedDepth png" and the
// quantized inverse depth of "32FC1; compressedDepth png") skips its 12-byte
// header. Anything else is an Error naming the topic, the encoding and the
// encodings supported.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "stillslam/io/ros2_messages.h"

namespace stillslam::ros2 {

cv::Mat image_to_mat(const Image& image, const std::string& topic);
// The fields of a sensor_msgs/Image whose pixels live elsewhere (a DDS sample
// in the live node): decoded exactly as image_to_mat decodes an Image.
struct ImageView {
  std::uint32_t height = 0, width = 0;
  std::string encoding;
  std::uint8_t is_bigendian = 0;
  std::uint32_t step = 0;
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;  // bytes at data
};
cv::Mat image_to_mat(const ImageView& image, const std::string& topic);
// Why image_to_mat / compressed_image_to_mat would refuse the encoding /
// format (naming topic, encoding and the supported ones), or nothing.
std::optional<std::string> unsupported(const Image& image, const std::string& topic);
std::optional<std::string> unsupported(const CompressedImage& image, const std::string& topic);
cv::Mat compressed_image_to_mat(const CompressedImage& image, const std::string& topic);

// The ROS encoding of an OpenCV image type: 8UC1 mono8, 8UC3 bgr8, 16UC1
// 16UC1, 32FC1 32FC1; Error for other types.
std::string ros_encoding(const cv::Mat& mat);
// 8UC1 -> mono8, 8UC3 -> bgr8, 16UC1 -> 16UC1, 32FC1 -> 32FC1; step = width * pixel size.
Image mat_to_image(const cv::Mat& mat, const Header& header);
// PNG of an 8-bit image ("png"), or a 16UC1 depth image as "16UC1; compressedDepth png".
CompressedImage mat_to_png(const cv::Mat& mat, const Header& header);

}  // namespace stillslam::ros2
