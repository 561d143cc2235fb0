#pragma once
// Rectifies a calibrated stereo pair, then remaps images. Pinhole cameras with
// radial-tangential distortion use cv::stereoRectify with alpha 0 (every
// rectified pixel is valid); KannalaBrandt8 (equidistant fisheye) pairs use
// cv::fisheye::stereoRectify with balance 0. Zero disparity at infinity; rows
// of the rectified pair are epipolar lines.
#include <opencv2/core.hpp>

#include "stillslam/geometry/camera_calibration.h"

namespace stillslam {

class StereoRectifier {
 public:
  // `raw` holds the unrectified cameras and T_c1_c2; `size` is the image
  // size of both cameras.
  // Throws Error for unsupported models or degenerate geometry.
  StereoRectifier(const StereoCalibration& raw, cv::Size size);

  cv::Mat rectify_left(const cv::Mat& image) const;
  cv::Mat rectify_right(const cv::Mat& image) const;
  // Where a raw pixel lands in the rectified image (e.g. to rectify keypoints).
  cv::Point2d rectify_left_point(const cv::Point2d& raw) const;
  cv::Point2d rectify_right_point(const cv::Point2d& raw) const;
  // Rectified intrinsics (same for both cameras), baseline, no distortion.
  const StereoCalibration& rectified() const { return rectified_; }
  cv::Size size() const { return size_; }
  // Rotation from the raw left camera frame into the rectified left frame
  // (poses of the rectified camera: T_raw_rect.linear() = R_left^T).
  const cv::Matx33d& left_rotation() const { return R1_; }

 private:
  cv::Point2d rectify_point(const cv::Point2d& raw, bool left) const;

  cv::Size size_;
  bool fisheye_ = false;
  cv::Mat K1_, D1_, K2_, D2_, R1m_, R2m_, P1_, P2_;
  cv::Mat map_left_x_, map_left_y_, map_right_x_, map_right_y_;
  cv::Matx33d R1_;
  StereoCalibration rectified_;
};

}  // namespace stillslam
