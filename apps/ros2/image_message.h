#pragma once
// sensor_msgs/Image to and from cv::Mat. Writing borrows: the message points
// into the image and the strings of an OutgoingImage, which must outlive the
// dds_write (it serializes at once). Reading copies into a new cv::Mat.
#include <cstdint>
#include <string>

#include <opencv2/core.hpp>

#include "sensor_msgs/msg/Image.h"

namespace stillslam::ros2 {

class OutgoingImage {
 public:
  // `image` is shared (not copied); a non-continuous one is copied.
  OutgoingImage(const cv::Mat& image, std::int64_t stamp_ns, const std::string& frame_id);
  OutgoingImage(const OutgoingImage&) = delete;
  OutgoingImage& operator=(const OutgoingImage&) = delete;
  const sensor_msgs_msg_dds__Image_& message() const { return message_; }

 private:
  cv::Mat image_;
  std::string encoding_, frame_id_;
  sensor_msgs_msg_dds__Image_ message_{};
};

// The dynamic mask as a mono8 image: 255 where features were kept out, 0
// elsewhere (whatever non-zero value the mask uses).
cv::Mat1b mask_image(const cv::Mat1b& mask);

// A copy of the message's pixels, decoded as a bag's Image is
// (io/ros2_image_convert.h: the same encodings, byte order and step checks).
cv::Mat image_from_message(const sensor_msgs_msg_dds__Image_& message, const std::string& topic);

}  // namespace stillslam::ros2
