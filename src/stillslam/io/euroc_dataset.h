#pragma once
// EuRoC MAV stereo sequences (ASL layout): mav0/cam0/data.csv +
// mav0/cam0/data/<ns>.png, the same for cam1, per-camera sensor.yaml
// (intrinsics, radial-tangential distortion, T_BS, resolution) and the IMU
// log mav0/imu0/data.csv. Left/right images are paired by timestamp and
// rectified on load.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "stillslam/io/file_dataset.h"
#include "stillslam/io/stereo_rectifier.h"

namespace stillslam {

struct ImuSample {
  double timestamp = 0;      // seconds
  Eigen::Vector3d gyro;      // rad/s, IMU frame
  Eigen::Vector3d accel;     // m/s^2, IMU frame
};

// One camera's sensor.yaml.
struct EurocCamera {
  CameraCalibration calibration;
  Eigen::Isometry3d T_body_cam = Eigen::Isometry3d::Identity();  // T_BS
};
EurocCamera read_euroc_camera(const std::filesystem::path& sensor_yaml);

class EurocDataset : public FileDataset {
 public:
  // `mav0` is the folder holding cam0/, cam1/ (and imu0/). The raw stereo
  // calibration comes from Settings when it describes an unrectified pair
  // (Camera2.* + Stereo.T_c1_c2, or LEFT/RIGHT blocks), else from the
  // sensor.yaml files (T_c1_c2 = inv(T_BS_cam0) * T_BS_cam1). For an already
  // rectified pair (zero distortion, parallel cameras) the remap is the identity.
  EurocDataset(const std::filesystem::path& mav0, const CameraSettings& settings, const DatasetOptions& options);

  std::string kind() const override { return "euroc"; }
  SensorType sensor() const override { return SensorType::Stereo; }
  std::size_t size() const override { return frames_.size(); }
  double timestamp(std::size_t i) const override { return frames_.at(i).timestamp; }
  std::optional<StereoCalibration> rectified_stereo() const override { return rectifier_->rectified(); }

  const std::vector<ImuSample>& imu() const { return imu_; }
  const StereoCalibration& raw_stereo() const { return raw_; }
  const StereoRectifier& rectifier() const { return *rectifier_; }
  // Frames in cam0 whose cam1 partner is missing (not within max_dt).
  std::size_t unpaired_frames() const { return unpaired_; }

 protected:
  SensorFrame read_frame(std::size_t i) const override;
  std::string frame_name(std::size_t i) const override { return frames_.at(i).left; }

 private:
  struct StereoFrame {
    double timestamp;
    std::string left, right;  // file names inside cam0/data, cam1/data
  };
  std::filesystem::path mav0_;
  std::vector<StereoFrame> frames_;
  std::vector<ImuSample> imu_;
  StereoCalibration raw_;
  std::unique_ptr<StereoRectifier> rectifier_;
  std::size_t unpaired_ = 0;
};

}  // namespace stillslam
