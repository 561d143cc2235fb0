#include "frame_assembler.h"

#include <opencv2/imgproc.hpp>

#include "ros_time.h"
#include "stillslam/core/error.h"

namespace stillslam::ros2 {

namespace {

void check_size(const cv::Mat& image, cv::Size expected, const std::string& topic, const std::string& settings_file) {
  if (expected.width > 0 && expected.height > 0 && image.size() != expected) {
    throw Error(topic + ": image is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                " but " + settings_file + " says Camera.width/height " + std::to_string(expected.width) +
                "x" + std::to_string(expected.height) + " (use the settings file made for this camera)");
  }
}

cv::Mat to_gray(const cv::Mat& image, const std::string& topic) {
  if (image.type() == CV_8UC1) return image;
  if (image.type() == CV_8UC3) {
    cv::Mat gray;
    cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
    return gray;
  }
  throw Error(topic + ": a camera image must be 8-bit (mono8, bgr8, rgb8, bgra8 or rgba8), not a depth encoding");
}

}  // namespace

SensorType sensor_of(const Settings& settings) {
  if (settings.stereo) return SensorType::Stereo;
  if (settings.rgbd) return SensorType::Rgbd;
  throw Error(settings.file.string() +
              ": describes neither a stereo pair (Camera2.* + Stereo.T_c1_c2, or Camera.bf) nor an RGB-D camera "
              "(DepthMapFactor); the ROS 2 node needs one of them");
}

FrameAssembler::FrameAssembler(const Settings& settings, bool rectified_input)
    : sensor_(sensor_of(settings)),
      size_(settings.camera.width, settings.camera.height),
      settings_file_(settings.file.string()),
      camera_(settings.camera) {
  if (sensor_ != SensorType::Stereo) return;
  if (settings.stereo->rectified) {
    rectified_ = settings.stereo;
    camera_ = rectified_->left;
    return;
  }
  if (size_.width <= 0 || size_.height <= 0) {
    throw Error(settings.file.string() +
                ": a raw stereo pair needs Camera.width and Camera.height for the ROS 2 node (it rectifies "
                "before the first image arrives)");
  }
  rectifier_ = std::make_unique<StereoRectifier>(*settings.stereo, size_);
  rectified_ = rectifier_->rectified();
  camera_ = rectified_->left;
  rectify_ = !rectified_input;
}

SensorFrame FrameAssembler::assemble(const ImagePair& pair, std::size_t index, const std::string& first_topic,
                                     const std::string& second_topic) const {
  SensorFrame frame;
  frame.index = index;
  frame.timestamp = seconds_from_nanoseconds(pair.first.stamp_ns);
  frame.name = first_topic + " @ " + std::to_string(pair.first.stamp_ns) + " ns";
  const cv::Mat& first = pair.first.image;
  const cv::Mat& second = pair.second.image;
  check_size(first, size_, first_topic, settings_file_);
  if (second.size() != first.size()) {
    throw Error(second_topic + ": image is " + std::to_string(second.cols) + "x" + std::to_string(second.rows) +
                " but " + first_topic + " sends " + std::to_string(first.cols) + "x" + std::to_string(first.rows) +
                " (both topics must come from one calibrated camera pair)");
  }
  if (sensor_ == SensorType::Stereo) {
    const cv::Mat left = to_gray(first, first_topic);
    const cv::Mat right = to_gray(second, second_topic);
    frame.gray = rectify_ ? rectifier_->rectify_left(left) : left;
    frame.right = rectify_ ? rectifier_->rectify_right(right) : right;
    if (first.channels() == 3) {
      frame.color = rectify_ ? rectifier_->rectify_left(first) : first;
    } else {
      cv::cvtColor(frame.gray, frame.color, cv::COLOR_GRAY2BGR);
    }
    return frame;
  }
  if (first.type() == CV_8UC3) {
    frame.color = first;
  } else {
    cv::cvtColor(to_gray(first, first_topic), frame.color, cv::COLOR_GRAY2BGR);
  }
  cv::cvtColor(frame.color, frame.gray, cv::COLOR_BGR2GRAY);
  if (second.type() == CV_32FC1) {
    frame.depth = second;
  } else if (second.type() == CV_16UC1) {
    second.convertTo(frame.depth, CV_32F, 0.001);  // REP 118: 16-bit depth is millimetres
  } else {
    throw Error(second_topic + ": a depth image must be 16UC1 (mm) or 32FC1 (m)");
  }
  return frame;
}

}  // namespace stillslam::ros2
