#pragma once
// KITTI odometry sequences: image_0/ (left) and image_1/ (right) rectified
// grayscale PNGs named %06d.png, times.txt (seconds) and calib.txt
// (P0/P1 projection matrices: fx, cx, cy from P0, baseline = -P1(0,3)/P1(0,0)).
#include <filesystem>
#include <string>
#include <vector>

#include "stillslam/io/file_dataset.h"

namespace stillslam {

// Rectified calibration from a KITTI calib.txt (image size left 0).
StereoCalibration read_kitti_calibration(const std::filesystem::path& calib_txt);

class KittiDataset : public FileDataset {
 public:
  // Uses calib.txt when present, else the Settings (which then must give
  // Camera.bf / Stereo.b). With both, settings intrinsics or bf that
  // differ from calib.txt's (by more than 1e-4 relative) are an Error
  // naming both. The image size comes from the first left image,
  // falling back to Camera.width/height.
  KittiDataset(const std::filesystem::path& folder, const CameraSettings& settings, const DatasetOptions& options);

  std::string kind() const override { return "kitti"; }
  SensorType sensor() const override { return SensorType::Stereo; }
  std::size_t size() const override { return times_.size(); }
  double timestamp(std::size_t i) const override { return times_.at(i); }
  std::optional<StereoCalibration> rectified_stereo() const override { return stereo_; }

 protected:
  SensorFrame read_frame(std::size_t i) const override;
  std::string frame_name(std::size_t i) const override;

 private:
  std::filesystem::path folder_;
  std::vector<double> times_;
  StereoCalibration stereo_;
};

}  // namespace stillslam
