#pragma once
// Camera calibration from a bag's sensor_msgs/CameraInfo (`stillslam run
// --camera-info-from-bag`): the CameraInfo topic of an image topic is its
// sibling `camera_info` (/cam0/image_raw -> /cam0/camera_info); its first
// message gives K, D (plumb_bob / rational_polynomial: radial-tangential;
// equidistant: KannalaBrandt8) and the image size. Two image topics and
// settings that do not ask for RGB-D make a stereo pair: both cameras raw,
// T_c1_c2 from the rectification rotations R and the right projection's
// P[3] = -fx * baseline (as ROS camera_calibration writes them).
#include <filesystem>
#include <string>
#include <vector>

#include "stillslam/io/bag_reader.h"
#include "stillslam/io/camera_settings.h"
#include "stillslam/io/ros2_messages.h"

namespace stillslam {

// "/cam0/image_raw" -> "/cam0/camera_info".
std::string camera_info_topic(const std::string& image_topic);
// The first CameraInfo of `topic`; Error naming the bag, the topic and the
// CameraInfo topics the bag has when missing.
ros2::CameraInfo read_first_camera_info(const BagReader& bag, const std::string& topic);
CameraCalibration calibration_from(const ros2::CameraInfo& info, const std::string& topic);

// Replaces the camera part of `settings` (camera, stereo, bf) by the bag's
// calibration for `image_topics` (as given to --topics).
void apply_bag_camera_info(CameraSettings& settings, const BagReader& bag, const std::vector<std::string>& image_topics);

}  // namespace stillslam
