#pragma once
// Random-access readers for image datasets (TUM RGB-D, EuRoC, KITTI odometry,
// ROS 2 bags: a bag folder or a bare .db3 / .mcap file).
// open_dataset() detects the layout from the folder contents (or takes a TUM
// association file as the path); a folder holding both a TUM and an EuRoC
// layout is read as EuRoC stereo when the settings describe a stereo pair,
// else as TUM RGB-D. Settings that ask for the other sensor (RGB-D settings
// on a stereo-only folder, stereo settings on a TUM folder) are an Error
// naming the settings to change. Every list's stamps are checked on opening
// (timestamp_check.h).
//
// Bad frames: by default load() throws stillslam::Error naming the file (missing
// image, unreadable or truncated PNG, 8-bit depth). With
// DatasetOptions::skip_bad_frames, load() instead logs a warning, counts the
// skip (skipped_frames()) and returns a frame with valid == false and the
// reason in `error`; size() and indices never change, so timestamps stay
// aligned with the frame list and callers simply ignore invalid frames.
#include <atomic>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "stillslam/core/sensor_frame.h"
#include "stillslam/io/camera_settings.h"

namespace stillslam {

struct DatasetOptions {
  double max_dt = 0.02;  // pairing tolerance, seconds: TUM rgb/depth, EuRoC cam0/cam1, bag topics
  std::optional<std::filesystem::path> association_file;  // TUM: use this instead of rgb.txt/depth.txt
  bool skip_bad_frames = false;
  // ROS 2 bags (bag_dataset.h): the image topics, LEFT,RIGHT (stereo) or
  // RGB,DEPTH (RGB-D), or one topic holding left|right side by side.
  std::vector<std::string> topics;
  bool side_by_side = false;
};

// Random access, read-only: concurrent load() calls on one dataset are safe.
class Dataset {
 public:
  virtual ~Dataset() = default;
  virtual std::string kind() const = 0;  // "tum", "euroc", "kitti"
  virtual SensorType sensor() const = 0;
  virtual std::size_t size() const = 0;
  virtual double timestamp(std::size_t i) const = 0;
  // Throws Error naming the file on a bad image (or flags the frame invalid
  // with skip_bad_frames); throws Error for an index >= size().
  virtual SensorFrame load(std::size_t i) const = 0;
  // Calibration after rectification for stereo datasets (baseline, rectified
  // intrinsics, no distortion); the SLAM system uses this instead of the raw
  // settings for stereo.
  virtual std::optional<StereoCalibration> rectified_stereo() const { return {}; }
  // Frames turned into invalid frames by skip_bad_frames so far.
  std::size_t skipped_frames() const { return skipped_.load(); }

 protected:
  void count_skip() const { ++skipped_; }

 private:
  mutable std::atomic<std::size_t> skipped_{0};
};

std::unique_ptr<Dataset> open_dataset(const std::filesystem::path& path, const CameraSettings& settings,
                                      const DatasetOptions& options = {});

}  // namespace stillslam
