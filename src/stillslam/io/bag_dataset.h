#pragma once
// A ROS 2 bag as a dataset: `--topics LEFT,RIGHT` (stereo), `--topics
// RGB,DEPTH` (RGB-D), or one topic with left|right side by side (stereo,
// DatasetOptions::side_by_side, as ZED drivers publish). The sensor follows
// the settings (a stereo pair or RGB-D); settings that say neither decide
// by the second topic's encoding (depth encodings mean RGB-D).
// Opening reads each image message's header stamp only; messages of the two
// topics are paired by header stamp within DatasetOptions::max_dt (unpaired
// counts are a warning) and load(i) reads and decodes pair i. Stereo pairs
// are rectified as in EuRoC (raw Camera2 / Stereo.T_c1_c2 settings), or used
// as they are with rectified settings (Camera.bf / Stereo.b). Depth: 16UC1
// in millimetres (ROS convention, DepthMapFactor is not used), 32FC1 in metres.
#include <memory>

#include "stillslam/io/bag_reader.h"
#include "stillslam/io/file_dataset.h"
#include "stillslam/io/stereo_rectifier.h"

namespace stillslam {

class BagDataset : public FileDataset {
 public:
  BagDataset(const std::filesystem::path& bag, const CameraSettings& settings, const DatasetOptions& options);

  std::string kind() const override { return "rosbag"; }
  SensorType sensor() const override { return sensor_; }
  std::size_t size() const override { return frames_.size(); }
  double timestamp(std::size_t i) const override { return frames_.at(i).timestamp; }
  std::optional<StereoCalibration> rectified_stereo() const override;

  const BagReader& bag() const { return *bag_; }
  // Messages of the first / second topic without a partner within max_dt.
  std::size_t unpaired_first() const { return unpaired_first_; }
  std::size_t unpaired_second() const { return unpaired_second_; }

 protected:
  SensorFrame read_frame(std::size_t i) const override;
  std::string frame_name(std::size_t i) const override;

 private:
  struct Pair {
    double timestamp;
    std::size_t first, second;  // message indices (second unused side by side)
  };
  cv::Mat decode(std::size_t message) const;  // as ros2_image_convert.h
  std::uint32_t require_image_topic(const std::string& name) const;

  std::unique_ptr<BagReader> bag_;
  std::vector<std::string> topics_;
  SensorType sensor_ = SensorType::Stereo;
  bool side_by_side_ = false;
  std::vector<Pair> frames_;
  std::size_t unpaired_first_ = 0, unpaired_second_ = 0;
  std::optional<StereoCalibration> stereo_;            // rectified settings as given
  std::unique_ptr<StereoRectifier> rectifier_;         // raw stereo settings
  cv::Size expected_size_;                              // per camera, 0 when unknown
};

}  // namespace stillslam
