#pragma once
// Rectifies a calibrated pinhole stereo pair (cv::stereoRectify with alpha 0,
// so every rectified pixel is valid, and zero disparity at infinity), then
// remaps images. Rows of the rectified pair are epipolar lines.
#include <opencv2/core.hpp>

#include "stillslam/geometry/camera_calibration.h"

namespace stillslam {

class StereoRectifier {
 public:
  // `raw` holds the unrectified cameras (pinhole, radial-tangential
  // distortion) and T_c1_c2; `size` is the image size of both cameras.
  // Throws Error for unsupported models or degenerate geometry.
  StereoRectifier(const StereoCalibration& raw, cv::Size size);

  cv::Mat rectify_left(const cv::Mat& image) const;
  cv::Mat rectify_right(const cv::Mat& image) const;
  // Rectified intrinsics (same for both cameras), baseline, no distortion.
  const StereoCalibration& rectified() const { return rectified_; }
  cv::Size size() const { return size_; }
  // Rotation from the raw left camera frame into the rectified left frame
  // (poses of the rectified camera: T_raw_rect.linear() = R_left^T).
  const cv::Matx33d& left_rotation() const { return R1_; }

 private:
  cv::Size size_;
  cv::Mat map_left_x_, map_left_y_, map_right_x_, map_right_y_;
  cv::Matx33d R1_;
  StereoCalibration rectified_;
};

}  // namespace stillslam
