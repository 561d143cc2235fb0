#pragma once
// Everything that defines a synthetic sequence. Two runs with equal options
// produce byte-identical files (the seed drives every random choice).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "stillslam/geometry/camera_calibration.h"

namespace stillslam::sim {

struct SimulationOptions {
  // Camera path: "walking_xyz" (TUM fr3/walking_xyz ground truth replayed),
  // "halfsphere", "rpy", "static", or the path of a TUM trajectory file.
  std::string trajectory = "walking_xyz";
  int frames = 300;            // at most this many frames (file trajectories may be shorter)
  double fps = 30.0;
  int width = 640, height = 480;
  // Pinhole like TUM fr3 but with square pixels (fx = fy) so that the stereo pair
  // stays exactly rectified through cv::stereoRectify; scaled with the image size.
  double fx = 535.4, fy = 535.4, cx = 320.1, cy = 247.6;

  std::uint64_t seed = 0;
  int people = 2;              // walking people
  int still_people = 0;        // people standing (almost) still in view
  bool moved_object = false;   // a box on the desk is picked up and carried away
  bool moved_chair = false;    // chair 1 behind the desk is pushed aside (DynamicObjects)
  bool no_people = false;      // drop every dynamic thing (static reference run)
  // A person walks right in front of the lens and hides (nearly) the whole view
  // from occlude_at for occlude_seconds (seconds since the first frame), e.g.
  // to test relocalization. In the ground-truth masks like everyone else.
  std::optional<double> occlude_at;
  double occlude_seconds = 1.0;
  // A crowd walks across the view close to the camera and covers most of it
  // from crowd_at for crowd_seconds (DynamicObjectsOptions::crowd_at).
  std::optional<double> crowd_at;
  double crowd_seconds = 3.0;

  bool stereo = false;         // also write a rectified EuRoC-layout stereo pair
  double baseline = 0.1;       // metres, stereo only
  // With stereo: the pair in gray like EuRoC's cameras; else in colour like a
  // ZED-type rig (the segmenter finds people far more reliably in colour).
  // `simulate --gray-stereo` sets both.
  bool stereo_gray = false;
  int noise = 0;               // 0 none, 1 realistic, 2 heavy
  int supersampling = 2;       // rays per pixel per axis for colour

  // Folder with textures/ and cutouts/ (the repo's data/). Empty: found via
  // find_data_dir().
  std::filesystem::path data_dir;
  // write_sequence: replace a sequence already in the output folder (its rgb/,
  // depth/, masks/ and mav0/cam*/data/ files are deleted first). Without it an
  // existing sequence there is an error.
  bool overwrite = false;
  // Written into settings.yaml as Segmentation.model. Empty: <data_dir>/../models/yolo11n-seg_384x512.onnx.
  std::filesystem::path segmentation_model;
};

// The intrinsics the options describe, at the options' image size.
CameraCalibration camera_from_options(const SimulationOptions& options);

}  // namespace stillslam::sim
