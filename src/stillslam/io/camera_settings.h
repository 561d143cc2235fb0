#pragma once
// The camera part of an ORB-SLAM3-compatible OpenCV YAML settings file: what
// the dataset readers need. Both the old key style (Camera.fx, Camera.bf,
// ThDepth, DepthMapFactor) and the new one (File.version "1.0", Camera1.*,
// Camera2.*, Stereo.*, RGBD.*) load unchanged. The sections of the other
// modules (ORB, Segmentation, Tracking, ...) are bound in settings/.
#include <filesystem>
#include <optional>

#include "stillslam/core/sensor_frame.h"
#include "stillslam/geometry/camera_calibration.h"

namespace stillslam {

class YamlReader;

struct CameraSettings {
  std::filesystem::path file;               // where it was read from
  // Left / RGB camera. `distortion` is empty when the file gives none or all
  // zeros; width/height are 0 when the file does not give them.
  CameraCalibration camera;
  // Set when the file describes a stereo pair: Camera2.* + Stereo.T_c1_c2 or
  // LEFT/RIGHT blocks (rectified = false: raw cameras to rectify), or
  // Camera.type "Rectified" / a baseline without DepthMapFactor (rectified =
  // true, left = right = camera).
  std::optional<StereoCalibration> stereo;
  // The file asks for an RGB-D camera: it gives DepthMapFactor (or
  // RGBD.DepthMapFactor) and describes no stereo pair. Neither this nor
  // `stereo`: the file does not say (old monocular-style keys).
  bool rgbd = false;
  double bf = 0;                            // baseline * fx (Camera.bf, or Stereo.b * fx)
  double th_depth = 40;                     // ThDepth / Stereo.ThDepth, in baselines
  double depth_map_factor = 5000;           // DepthMapFactor / RGBD.DepthMapFactor
  double fps = 30;                          // Camera.fps
  // Camera.RGB: 1 = the dataset's images are RGB-ordered (TUM), 0 = BGR. The
  // readers always hand out BGR (cv::imread order) so nothing converts on it.
  bool rgb = true;

  // Depth (metres) below which a stereo/RGB-D point counts as close:
  // th_depth * baseline, baseline = bf / fx. 0 when there is no baseline.
  double close_depth() const;
  double baseline() const;  // bf / fx, 0 when unknown
};

// Reads and validates the camera keys; throws stillslam::Error naming the file
// and the offending key. Keys of other sections are not looked at.
CameraSettings read_camera_settings(const YamlReader& yaml);
CameraSettings load_camera_settings(const std::filesystem::path& yaml);

}  // namespace stillslam
