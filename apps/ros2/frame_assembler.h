#pragma once
// Turns a pair of image messages into the SensorFrame the System takes, the
// way the dataset readers build theirs: stereo images to gray (colour kept
// for segmentation) and, when the settings describe a raw stereo pair and the
// images are not already rectified, rectified with the settings' calibration;
// RGB-D colour to BGR + gray, depth to metres (32FC1 as is, 16UC1 in
// millimetres as ROS 2 depth drivers publish it). Images of another size
// than the settings' are an Error naming the topic.
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "stamp_pairer.h"
#include "stillslam/core/sensor_frame.h"
#include "stillslam/io/stereo_rectifier.h"
#include "stillslam/settings/settings.h"

namespace stillslam::ros2 {

// Stereo when the settings describe a stereo pair, RGB-D when they give
// DepthMapFactor; Error naming the file otherwise.
SensorType sensor_of(const Settings& settings);

class FrameAssembler {
 public:
  // rectified_input: the images are already rectified with the settings'
  // raw stereo calibration (as `stillslam ros2-replay` publishes them).
  FrameAssembler(const Settings& settings, bool rectified_input);
  SensorType sensor() const { return sensor_; }
  // The calibration the System works in (stereo), as the dataset readers give it.
  std::optional<StereoCalibration> rectified_stereo() const { return rectified_; }
  // The camera the System's images are in: the rectified left camera, or the RGB-D camera.
  const CameraCalibration& camera() const { return camera_; }
  // `topics` name the two inputs for messages, "left,right" style.
  SensorFrame assemble(const ImagePair& pair, std::size_t index, const std::string& first_topic,
                       const std::string& second_topic) const;

 private:
  SensorType sensor_;
  cv::Size size_;  // from the settings; 0x0 when they do not say
  std::string settings_file_;
  bool rectify_ = false;
  std::unique_ptr<StereoRectifier> rectifier_;
  std::optional<StereoCalibration> rectified_;
  CameraCalibration camera_;
};

}  // namespace stillslam::ros2
