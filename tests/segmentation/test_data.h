#pragma once
// Paths used by the segmentation tests. The shipped model and tests/segmentation/data
// are in the repository; ../shared is optional (tests that need it skip).
#include <filesystem>
#include <string>

namespace stillslam::test {

inline std::string shipped_model() { return std::string(STILLSLAM_SOURCE_DIR) + "/models/yolo11n-seg_384x512.onnx"; }
inline std::string bus_image() { return std::string(STILLSLAM_SOURCE_DIR) + "/tests/segmentation/data/bus.jpg"; }
inline std::string shared_model(const std::string& file) {
  return std::string(STILLSLAM_SHARED_DIR) + "/models/yolo-seg/" + file;
}
inline bool exists(const std::string& path) { return std::filesystem::is_regular_file(path); }

}  // namespace stillslam::test
