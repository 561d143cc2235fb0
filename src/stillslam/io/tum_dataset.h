#pragma once
// TUM RGB-D sequences: rgb/ and depth/ PNGs listed in rgb.txt and depth.txt
// (associated like TUM's associate.py) or in an association file
// "t_rgb rgb/x.png t_depth depth/y.png". Frame timestamps are the RGB ones.
//
// Colour order: TUM stores RGB images (Camera.RGB: 1); cv::imread returns
// them as BGR, and `color` stays BGR, so no conversion depends on Camera.RGB.
#include <filesystem>
#include <string>
#include <vector>

#include "stillslam/io/file_dataset.h"

namespace stillslam {

struct TumPair {
  double rgb_time = 0;
  std::string rgb_file;  // relative to the sequence folder
  double depth_time = 0;
  std::string depth_file;
};

// Reads an association file (either column order: rgb first or depth first).
std::vector<TumPair> read_tum_associations(const std::filesystem::path& file);
// Associates rgb.txt and depth.txt of `folder` within max_dt seconds.
std::vector<TumPair> associate_tum_lists(const std::filesystem::path& rgb_list,
                                         const std::filesystem::path& depth_list, double max_dt);

class TumDataset : public FileDataset {
 public:
  // Throws Error when the lists are missing or empty.
  TumDataset(const std::filesystem::path& folder, const CameraSettings& settings, const DatasetOptions& options);

  std::string kind() const override { return "tum"; }
  SensorType sensor() const override { return SensorType::Rgbd; }
  std::size_t size() const override { return pairs_.size(); }
  double timestamp(std::size_t i) const override { return pairs_.at(i).rgb_time; }
  const std::vector<TumPair>& pairs() const { return pairs_; }
  // The list the frames came from (association file or rgb.txt).
  const std::filesystem::path& source() const { return source_; }

 protected:
  SensorFrame read_frame(std::size_t i) const override;
  std::string frame_name(std::size_t i) const override { return pairs_.at(i).rgb_file; }

 private:
  std::filesystem::path folder_;
  std::filesystem::path source_;
  double depth_map_factor_;
  cv::Size expected_size_;  // Camera.width/height when the settings give them
  std::vector<TumPair> pairs_;
};

}  // namespace stillslam
