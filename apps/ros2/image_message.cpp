#include "image_message.h"

#include <opencv2/imgproc.hpp>

#include "ros_time.h"
#include "stillslam/io/ros2_image_convert.h"
#include "stillslam/core/error.h"

namespace stillslam::ros2 {

OutgoingImage::OutgoingImage(const cv::Mat& image, std::int64_t stamp_ns, const std::string& frame_id)
    : image_(image.isContinuous() ? image : image.clone()), encoding_(ros_encoding(image)), frame_id_(frame_id) {
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
  return image_to_mat(ImageView{m.height, m.width, m.encoding != nullptr ? m.encoding : "", m.is_bigendian, m.step,
                                m.data._buffer, m.data._length},
                      topic);
}

}  // namespace stillslam::ros2
