#pragma once
// The image topic options shared by `stillslam ros2` and `ros2-replay`:
// --left/--right (stereo) or --rgb/--depth (RGB-D), with ROS camera-driver
// style defaults.
#include <CLI/CLI.hpp>

#include <string>
#include <utility>

#include "stillslam/core/sensor_frame.h"

namespace stillslam::ros2 {

struct ImageTopicArgs {
  std::string left, right, rgb, depth;
};
void add_image_topic_options(CLI::App& cmd, ImageTopicArgs& args);

// The two topics for `sensor` (left/right or colour/depth), defaults filled
// in. Error when the other sensor's topics are given; `source` (the settings
// or the folder) names what decided the sensor.
std::pair<std::string, std::string> image_topics(const ImageTopicArgs& args, SensorType sensor,
                                                 const std::string& source);

}  // namespace stillslam::ros2
