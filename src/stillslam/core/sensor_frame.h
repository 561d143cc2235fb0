#pragma once
// What a camera delivers for one instant, and which kind of camera it is.
// Readers (io/, sim/) fill SensorFrames; the frame builder consumes them.
#include <cstddef>
#include <string>

#include <opencv2/core.hpp>

namespace stillslam {

enum class SensorType { Monocular, Stereo, Rgbd };

// "monocular", "stereo", "rgbd".
inline const char* to_string(SensorType sensor) {
  switch (sensor) {
    case SensorType::Monocular: return "monocular";
    case SensorType::Stereo: return "stereo";
    case SensorType::Rgbd: return "rgbd";
  }
  return "unknown";
}

struct SensorFrame {
  std::size_t index = 0;
  double timestamp = 0;  // seconds
  cv::Mat color;  // 8UC3 BGR (for segmentation); for gray datasets a BGR copy of the gray image
  cv::Mat gray;   // 8UC1, rectified for stereo
  cv::Mat right;  // 8UC1 rectified right image (stereo), else empty
  cv::Mat depth;  // CV_32F metres (RGB-D), 0 = invalid; else empty
  std::string name;  // image file name, for messages
  bool valid = true;   // false only when skip_bad_frames turned an error into a skip
  std::string error;   // why the frame is invalid
};

}  // namespace stillslam
