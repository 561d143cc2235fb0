#pragma once
// Pinhole camera (fx, fy, cx, cy) with optional lens distortion handled only
// at the keypoint level: every other stage works on undistorted pixels, so
// project()/unproject() are the ideal pinhole maps. `bf` (= fx * baseline in
// metres) turns a depth into a virtual right-image coordinate u_r = u - bf/z,
// the same convention for rectified stereo and RGB-D.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "stillslam/geometry/camera_calibration.h"

namespace stillslam {

class PinholeCamera {
 public:
  // Throws stillslam::Error when fx/fy are not positive or the image size is
  // empty. KannalaBrandt8 calibrations are accepted: their distortion is
  // removed with the fisheye model and the rest is pinhole.
  explicit PinholeCamera(const CameraCalibration& calibration, double bf = 0);

  // Ideal pinhole projection of a point in the camera frame (z must be > 0).
  Eigen::Vector2d project(const Eigen::Vector3d& p_cam) const {
    const double inv_z = 1.0 / p_cam.z();
    return {fx_ * p_cam.x() * inv_z + cx_, fy_ * p_cam.y() * inv_z + cy_};
  }
  // Virtual right-image u coordinate of a camera-frame point (needs bf > 0).
  double project_right_u(const Eigen::Vector3d& p_cam) const {
    return project(p_cam).x() - bf_ / p_cam.z();
  }
  // Inside the undistorted image bounds.
  bool in_image(const Eigen::Vector2d& pixel) const;
  // Point in the camera frame at the given depth (z) along an undistorted pixel.
  Eigen::Vector3d unproject(const Eigen::Vector2d& pixel_undistorted, double depth) const {
    return {(pixel_undistorted.x() - cx_) * inv_fx_ * depth,
            (pixel_undistorted.y() - cy_) * inv_fy_ * depth, depth};
  }
  // Normalized image coordinates (x/z, y/z, 1) of an undistorted pixel.
  Eigen::Vector3d normalized(const Eigen::Vector2d& pixel_undistorted) const {
    return unproject(pixel_undistorted, 1.0);
  }

  double fx() const { return fx_; }
  double fy() const { return fy_; }
  double cx() const { return cx_; }
  double cy() const { return cy_; }
  double inv_fx() const { return inv_fx_; }
  double inv_fy() const { return inv_fy_; }
  double bf() const { return bf_; }
  double baseline() const { return fx_ > 0 ? bf_ / fx_ : 0.0; }
  int width() const { return calibration_.width; }
  int height() const { return calibration_.height; }
  const CameraCalibration& calibration() const { return calibration_; }
  // 3x3 intrinsic matrix (CV_64F).
  cv::Mat K() const;

  // Undistorted image bounds (min/max x, y after undistorting the image
  // corners and edge midpoints); the full image when there is no distortion.
  cv::Rect2f undistorted_bounds() const { return bounds_; }
  // Keypoints with undistorted pt (cv::undistortPoints with P = K and
  // undistort_criteria(); cv::fisheye for KannalaBrandt8); all other
  // keypoint fields are kept. A copy when there is no distortion.
  std::vector<cv::KeyPoint> undistort(const std::vector<cv::KeyPoint>& keypoints) const;
  // Undistort raw pixel coordinates.
  std::vector<cv::Point2f> undistort(const std::vector<cv::Point2f>& pixels) const;
  bool has_distortion() const;
  // Iteration limits used for the pinhole model's undistortion.
  static cv::TermCriteria undistort_criteria();

 private:
  CameraCalibration calibration_;
  double fx_, fy_, cx_, cy_, inv_fx_, inv_fy_, bf_;
  cv::Rect2f bounds_;
};

}  // namespace stillslam
