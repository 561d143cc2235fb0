#pragma once
// Plain calibration numbers as read from a settings file or a dataset's own
// calibration. geometry/ builds camera models from this; io/ fills it.
#include <Eigen/Geometry>
#include <optional>
#include <vector>

namespace stillslam {

enum class CameraModel { Pinhole, KannalaBrandt8 };

struct CameraCalibration {
  CameraModel model = CameraModel::Pinhole;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  // Pinhole: k1 k2 p1 p2 [k3] (OpenCV order). KannalaBrandt8: k1 k2 k3 k4.
  std::vector<double> distortion;
  int width = 0, height = 0;
};

// A pinhole camera without distortion (synthetic scenes, tests).
inline CameraCalibration pinhole_calibration(double fx, double fy, double cx, double cy, int width, int height) {
  CameraCalibration c;
  c.fx = fx;
  c.fy = fy;
  c.cx = cx;
  c.cy = cy;
  c.width = width;
  c.height = height;
  return c;
}

// A stereo pair. When `rectified` is true both images are already rectified
// (left calibration holds the rectified intrinsics, no distortion) and only
// the baseline matters; otherwise T_c1_c2 and the right calibration are used
// to rectify.
struct StereoCalibration {
  CameraCalibration left;
  CameraCalibration right;
  Eigen::Isometry3d T_c1_c2 = Eigen::Isometry3d::Identity();  // right camera in left frame
  double baseline = 0;  // metres
  bool rectified = false;
};

}  // namespace stillslam
