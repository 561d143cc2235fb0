#pragma once
// The camera and point descriptors of the image-free synthetic scenes
// (tests/map/synthetic_scene.h for map/tracking/mapping, tests/loop/
// cylinder_world.h for the loop and map-merge scenes). Included by relative
// path: benches include those scenes without tests/ on the include path.
#include <array>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <random>

#include "stillslam/features/orb_options.h"
#include "stillslam/map/camera_setup.h"

namespace stillslam::test {

// 640x480 pinhole, f = 500 px, bf = 40 (an 8 cm baseline), close depth 40
// baselines, the default ORB pyramid.
inline std::shared_ptr<CameraSetup> synthetic_camera_setup() {
  const CameraCalibration calib = pinhole_calibration(500, 500, 320, 240, 640, 480);
  return std::make_shared<CameraSetup>(PinholeCamera(calib, 40.0), ScalePyramid(OrbOptions{}), 40.0 / 500 * 40);
}

using SceneDescriptor = std::array<std::uint8_t, 32>;

// 32 uniformly random bytes: distinct points get descriptors far apart.
inline SceneDescriptor random_descriptor(std::mt19937& rng) {
  std::uniform_int_distribution<int> byte(0, 255);
  SceneDescriptor d{};
  for (auto& b : d) b = static_cast<std::uint8_t>(byte(rng));
  return d;
}

// The descriptor as a 1 x 32 CV_8U row (its own copy).
inline cv::Mat descriptor_row(const SceneDescriptor& d) {
  return cv::Mat(1, 32, CV_8U, const_cast<std::uint8_t*>(d.data())).clone();
}

}  // namespace stillslam::test
