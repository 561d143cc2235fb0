#include "stillslam/sim/settings_files.h"

#include <fstream>
#include <opencv2/core.hpp>

#include "stillslam/core/error.h"
#include "stillslam/core/text_file.h"

namespace stillslam::sim {
namespace {

void camera_block(std::ofstream& out, const CameraCalibration& c, int index) {
  out << cv::format("Camera%d.fx: %.6f\nCamera%d.fy: %.6f\nCamera%d.cx: %.6f\nCamera%d.cy: %.6f\n",
                    index, c.fx, index, c.fy, index, c.cx, index, c.cy)
      << cv::format("Camera%d.k1: 0.0\nCamera%d.k2: 0.0\nCamera%d.p1: 0.0\nCamera%d.p2: 0.0\n\n",
                    index, index, index, index);
}

void common_tail(std::ofstream& out, const std::filesystem::path& model, int features) {
  out << "ORBextractor.nFeatures: " << features << "\n"
      << "ORBextractor.scaleFactor: 1.2\nORBextractor.nLevels: 8\n"
      << "ORBextractor.iniThFAST: 20\nORBextractor.minThFAST: 7\n\n"
      << "# Dynamic-object segmentation; the simulator's masks/ hold the ground truth.\n"
      << "Segmentation.enabled: 1\n"
      << "Segmentation.model: \"" << model.string() << "\"\n"
      << "Segmentation.classes: \"person\"\n"
      << "Segmentation.scoreThreshold: 0.25\nSegmentation.nmsIouThreshold: 0.45\n"
      << "Segmentation.maskThreshold: 0.5\nSegmentation.maskDilation: 10\nSegmentation.holdFrames: 10\nSegmentation.threads: 1\n";
}

}  // namespace

void write_rgbd_settings(const std::filesystem::path& file, const CameraCalibration& c,
                         const SimulationOptions& o, const std::filesystem::path& model) {
  auto out = open_for_writing(file);
  out << "%YAML:1.0\n# stillslam simulate: synthetic RGB-D sequence (pinhole like TUM fr3, no distortion).\n"
      << "File.version: \"1.0\"\nCamera.type: \"PinHole\"\n\n";
  camera_block(out, c, 1);
  out << "Camera.width: " << c.width << "\nCamera.height: " << c.height << "\n"
      << "Camera.fps: " << o.fps << "\nCamera.RGB: 1\n\n"
      << "# Kinect-like virtual stereo baseline (bf = 40 px at fx 535.4) and close/far threshold.\n"
      << "Stereo.b: 0.0747\nStereo.ThDepth: 40.0\n\n"
      << "RGBD.DepthMapFactor: 5000.0\n\n";
  common_tail(out, model, 1000);
}

void write_stereo_settings(const std::filesystem::path& file, const CameraCalibration& c,
                           const SimulationOptions& o, const std::filesystem::path& model) {
  auto out = open_for_writing(file);
  out << "%YAML:1.0\n# stillslam simulate: synthetic rectified stereo pair (EuRoC layout in mav0/).\n"
      << "File.version: \"1.0\"\nCamera.type: \"PinHole\"\n\n";
  camera_block(out, c, 1);
  camera_block(out, c, 2);
  out << "Stereo.T_c1_c2: !!opencv-matrix\n  rows: 4\n  cols: 4\n  dt: d\n"
      << cv::format("  data: [1.0, 0.0, 0.0, %.6f,\n         0.0, 1.0, 0.0, 0.0,\n"
                    "         0.0, 0.0, 1.0, 0.0,\n         0.0, 0.0, 0.0, 1.0]\n\n",
                    o.baseline)
      << "Camera.width: " << c.width << "\nCamera.height: " << c.height << "\n"
      << "Camera.fps: " << o.fps << "\nCamera.RGB: 1\n\n"
      << "Stereo.ThDepth: 40.0\n\n";
  // Only about half the left keypoints find their right match (fewer when
  // people hide part of the view), so stereo extracts more than RGB-D's 1000
  // to get as many keypoints with depth.
  common_tail(out, model, 2000);
}

void write_euroc_sensor_yaml(const std::filesystem::path& file, const CameraCalibration& c,
                             double x_offset, double fps, int index) {
  auto out = open_for_writing(file);
  out << "%YAML:1.0\n# General sensor definitions.\nsensor_type: camera\n"
      << "comment: stillslam simulate cam" << index << " (rectified pair, body frame = cam0)\n\n"
      << "# Sensor extrinsics wrt. the body-frame.\nT_BS:\n  cols: 4\n  rows: 4\n"
      << cv::format("  data: [1.0, 0.0, 0.0, %.6f,\n         0.0, 1.0, 0.0, 0.0,\n"
                    "         0.0, 0.0, 1.0, 0.0,\n         0.0, 0.0, 0.0, 1.0]\n\n",
                    x_offset)
      << "# Camera specific definitions.\n"
      << "rate_hz: " << fps << "\nresolution: [" << c.width << ", " << c.height << "]\n"
      << "camera_model: pinhole\n"
      << cv::format("intrinsics: [%.6f, %.6f, %.6f, %.6f] #fu, fv, cu, cv\n", c.fx, c.fy, c.cx, c.cy)
      << "distortion_model: radial-tangential\n"
      << "distortion_coefficients: [0.0, 0.0, 0.0, 0.0]\n";
}

}  // namespace stillslam::sim
