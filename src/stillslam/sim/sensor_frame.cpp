#include "stillslam/sim/sensor_frame.h"

#include <opencv2/imgproc.hpp>

namespace stillslam::sim {

SensorFrame to_sensor_frame(const SimFrame& frame, SensorType sensor) {
  SensorFrame s;
  s.index = static_cast<std::size_t>(frame.index);
  s.timestamp = frame.timestamp;
  s.color = frame.bgr;
  cv::cvtColor(frame.bgr, s.gray, cv::COLOR_BGR2GRAY);
  if (sensor == SensorType::Stereo) {
    s.right = frame.right_gray;
  } else {
    s.depth = frame.depth;
  }
  s.name = "sim" + std::to_string(frame.index);
  return s;
}

}  // namespace stillslam::sim
