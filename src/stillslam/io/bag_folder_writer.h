#pragma once
// Writes a dataset folder as a ROS 2 bag, so bags can be made without ROS
// (`stillslam bag-write`, the tests, the replay tool's inputs):
// - EuRoC (mav0/cam0, cam1): /cam0/image_raw and /cam1/image_raw, and
//   /cam0/camera_info, /cam1/camera_info from sensor.yaml (K, D, and the
//   stereo rectification R, P of cv::stereoRectify, as ROS camera_calibration
//   writes them; P of the right camera carries -fx * baseline).
// - TUM RGB-D (rgb.txt + depth.txt): /camera/rgb/image_color and
//   /camera/depth/image (16UC1 millimetres, converted with `depth_map_factor`).
// Images are stored raw (sensor_msgs/Image: mono8 / bgr8 / 16UC1) or as PNG
// (sensor_msgs/CompressedImage: "png", depth "16UC1; compressedDepth png");
// header stamps and log times are the dataset's timestamps.
#include <filesystem>
#include <string>

#include "stillslam/io/bag_writer.h"

namespace stillslam {

struct BagFolderWriteOptions {
  BagWriterOptions bag;
  std::string images = "raw";     // "raw" or "png"
  double depth_map_factor = 5000;  // TUM depth PNG units per metre
  std::size_t max_frames = 0;      // 0: all
  void check() const;
};

struct BagFolderWriteResult {
  std::string layout;  // "euroc" or "tum"
  std::size_t frames = 0;
  std::size_t messages = 0;
  std::size_t missing_images = 0;  // listed but not on disk (a warning; e.g. a trimmed clip)
  std::vector<std::string> image_topics;  // for --topics
};

BagFolderWriteResult write_folder_as_bag(const std::filesystem::path& folder, const std::filesystem::path& out,
                                         const BagFolderWriteOptions& options);

}  // namespace stillslam
