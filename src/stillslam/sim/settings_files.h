#pragma once
// settings.yaml / settings_stereo.yaml next to a simulated sequence, in the
// key style of config/tum_fr3.yaml and config/euroc.yaml (ORB-SLAM3 new-style
// keys, plus Segmentation.*), so `stillslam run --config` loads them unchanged.
#include <filesystem>

#include "stillslam/geometry/camera_calibration.h"
#include "stillslam/sim/simulation_options.h"

namespace stillslam::sim {

void write_rgbd_settings(const std::filesystem::path& file, const CameraCalibration& camera,
                         const SimulationOptions& options, const std::filesystem::path& model);
void write_stereo_settings(const std::filesystem::path& file, const CameraCalibration& camera,
                           const SimulationOptions& options, const std::filesystem::path& model);
// EuRoC sensor.yaml of one camera of the rectified pair (body frame = cam0).
void write_euroc_sensor_yaml(const std::filesystem::path& file, const CameraCalibration& camera,
                             double x_offset, double fps, int index);

}  // namespace stillslam::sim
