#include "image_topic_args.h"

#include "stillslam/core/error.h"

namespace stillslam::ros2 {

void add_image_topic_options(CLI::App& cmd, ImageTopicArgs& args) {
  cmd.add_option("--left", args.left, "left image topic (stereo; default camera/left/image_raw)");
  cmd.add_option("--right", args.right, "right image topic (stereo; default camera/right/image_raw)");
  cmd.add_option("--rgb", args.rgb, "colour image topic (RGB-D; default camera/color/image_raw)");
  cmd.add_option("--depth", args.depth, "depth image topic, 16UC1 mm or 32FC1 m (RGB-D; default camera/depth/image_raw)");
}

std::pair<std::string, std::string> image_topics(const ImageTopicArgs& args, SensorType sensor,
                                                 const std::string& source) {
  const auto or_default = [](const std::string& given, const char* fallback) {
    return given.empty() ? std::string(fallback) : given;
  };
  if (sensor == SensorType::Stereo) {
    if (!args.rgb.empty() || !args.depth.empty()) {
      throw Error(source + " describes a stereo camera: give --left/--right, not --rgb/--depth");
    }
    return {or_default(args.left, "camera/left/image_raw"), or_default(args.right, "camera/right/image_raw")};
  }
  if (!args.left.empty() || !args.right.empty()) {
    throw Error(source + " describes an RGB-D camera: give --rgb/--depth, not --left/--right");
  }
  return {or_default(args.rgb, "camera/color/image_raw"), or_default(args.depth, "camera/depth/image_raw")};
}

}  // namespace stillslam::ros2
