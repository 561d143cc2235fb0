#include "image_message.h"

#include <cstring>

#include <opencv2/imgproc.hpp>

#include "ros_time.h"
#include "stillslam/core/error.h"

namespace stillslam::ros2 {

std::string image_encoding(const cv::Mat& image) {
  switch (image.type()) {
    case CV_8UC1: return "mono8";
    case CV_8UC3: return "bgr8";
    case CV_16UC1: return "16UC1";
    case CV_32FC1: return "32FC1";
    default: break;
  }
  throw Error("no ROS image encoding for OpenCV type " + std::to_string(image.type()) +
              " (mono8, bgr8, 16UC1 and 32FC1 are published)");
}

OutgoingImage::OutgoingImage(const cv::Mat& image, std::int64_t stamp_ns, const std::string& frame_id)
    : image_(image.isContinuous() ? image : image.clone()), encoding_(image_encoding(image)), frame_id_(frame_id) {
  message_.header.stamp = stamp_from_nanoseconds(stamp_ns);
  message_.header.frame_id = frame_id_.data();
  message_.height = static_cast<std::uint32_t>(image_.rows);
  message_.width = static_cast<std::uint32_t>(image_.cols);
  message_.encoding = encoding_.data();
  message_.is_bigendian = 0;
  message_.step = static_cast<std::uint32_t>(image_.cols * image_.elemSize());
  const std::size_t bytes = image_.total() * image_.elemSize();
  message_.data._maximum = message_.data._length = static_cast<std::uint32_t>(bytes);
  message_.data._buffer = image_.data;
  message_.data._release = false;
}

cv::Mat1b mask_image(const cv::Mat1b& mask) {
  cv::Mat1b out;
  cv::compare(mask, 0, out, cv::CMP_NE);  // 255 where non-zero
  return out;
}

cv::Mat image_from_message(const sensor_msgs_msg_dds__Image_& m, const std::string& topic) {
  const std::string encoding = m.encoding != nullptr ? m.encoding : "";
  int type = -1;
  int code = -1;  // colour conversion to BGR, if any
  if (encoding == "mono8" || encoding == "8UC1") {
    type = CV_8UC1;
  } else if (encoding == "bgr8" || encoding == "8UC3") {
    type = CV_8UC3;
  } else if (encoding == "rgb8") {
    type = CV_8UC3;
    code = cv::COLOR_RGB2BGR;
  } else if (encoding == "bgra8") {
    type = CV_8UC4;
    code = cv::COLOR_BGRA2BGR;
  } else if (encoding == "rgba8") {
    type = CV_8UC4;
    code = cv::COLOR_RGBA2BGR;
  } else if (encoding == "16UC1" || encoding == "mono16") {
    type = CV_16UC1;
  } else if (encoding == "32FC1") {
    type = CV_32FC1;
  } else {
    throw Error(topic + ": image encoding '" + encoding +
                "' is not supported (use mono8, bgr8, rgb8, bgra8, rgba8, 16UC1/mono16 depth in mm, or 32FC1 depth in m)");
  }
  const std::size_t pixel = CV_ELEM_SIZE(type);
  if (m.is_bigendian != 0 && CV_ELEM_SIZE1(type) > 1) {
    throw Error(topic + ": big-endian " + encoding + " images are not supported (publish little-endian data)");
  }
  if (m.width == 0 || m.height == 0 || m.step < m.width * pixel ||
      static_cast<std::size_t>(m.data._length) < static_cast<std::size_t>(m.step) * m.height) {
    throw Error(topic + ": image message of " + std::to_string(m.width) + "x" + std::to_string(m.height) + " " +
                encoding + " has step " + std::to_string(m.step) + " and " + std::to_string(m.data._length) +
                " bytes of data: it does not hold the image");
  }
  const cv::Mat view(static_cast<int>(m.height), static_cast<int>(m.width), type, m.data._buffer, m.step);
  cv::Mat out;
  if (code >= 0) {
    cv::cvtColor(view, out, code);
  } else {
    out = view.clone();
  }
  return out;
}

}  // namespace stillslam::ros2
