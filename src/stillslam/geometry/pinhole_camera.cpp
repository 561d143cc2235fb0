#include "stillslam/geometry/pinhole_camera.h"

#include <algorithm>
#include <opencv2/calib3d.hpp>
#include <string>

#include "stillslam/core/error.h"

namespace stillslam {
namespace {

cv::Mat distortion_coefficients(const CameraCalibration& c) {
  cv::Mat d(static_cast<int>(c.distortion.size()), 1, CV_64F);
  for (std::size_t i = 0; i < c.distortion.size(); ++i) d.at<double>(static_cast<int>(i)) = c.distortion[i];
  return d;
}

}  // namespace

cv::TermCriteria PinholeCamera::undistort_criteria() {
  return {cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 1e-3};
}

PinholeCamera::PinholeCamera(const CameraCalibration& calibration, double bf)
    : calibration_(calibration),
      fx_(calibration.fx),
      fy_(calibration.fy),
      cx_(calibration.cx),
      cy_(calibration.cy),
      inv_fx_(0),
      inv_fy_(0),
      bf_(bf) {
  if (!(fx_ > 0) || !(fy_ > 0)) {
    throw Error("camera calibration: fx and fy must be positive (got fx=" + std::to_string(fx_) +
                ", fy=" + std::to_string(fy_) + "); check Camera1.fx/fy in the settings file");
  }
  if (calibration.width <= 0 || calibration.height <= 0) {
    throw Error("camera calibration: image size must be positive (got " + std::to_string(calibration.width) +
                "x" + std::to_string(calibration.height) + "); set Camera.width/height in the settings file");
  }
  if (calibration.model == CameraModel::KannalaBrandt8 && calibration.distortion.size() != 4) {
    throw Error("camera calibration: the KannalaBrandt8 model needs 4 distortion coefficients k1..k4 (got " +
                std::to_string(calibration.distortion.size()) + ")");
  }
  if (calibration.model == CameraModel::Pinhole && !calibration.distortion.empty()) {
    const auto n = calibration.distortion.size();
    if (n != 4 && n != 5 && n != 8) {
      throw Error("camera calibration: pinhole distortion needs 4, 5 or 8 coefficients (k1 k2 p1 p2 [k3 ...]), got " +
                  std::to_string(n));
    }
  }
  if (bf_ < 0) throw Error("camera calibration: stereo bf must not be negative (got " + std::to_string(bf_) + ")");
  inv_fx_ = 1.0 / fx_;
  inv_fy_ = 1.0 / fy_;

  const float w = static_cast<float>(calibration.width), h = static_cast<float>(calibration.height);
  if (!has_distortion()) {
    bounds_ = cv::Rect2f(0.f, 0.f, w, h);
  } else {
    const std::vector<cv::Point2f> border = {{0.f, 0.f}, {w / 2, 0.f}, {w, 0.f}, {w, h / 2},
                                             {w, h},     {w / 2, h},  {0.f, h}, {0.f, h / 2}};
    const auto u = undistort(border);
    // Corners bound x/y on their sides; take the extremes of the left/right
    // (top/bottom) samples so barrel and pincushion both give a valid box.
    const float min_x = std::min({u[0].x, u[6].x, u[7].x});
    const float max_x = std::max({u[2].x, u[3].x, u[4].x});
    const float min_y = std::min({u[0].y, u[1].y, u[2].y});
    const float max_y = std::max({u[4].y, u[5].y, u[6].y});
    bounds_ = cv::Rect2f(min_x, min_y, max_x - min_x, max_y - min_y);
  }
}

bool PinholeCamera::in_image(const Eigen::Vector2d& pixel) const {
  return pixel.x() >= bounds_.x && pixel.x() < bounds_.x + bounds_.width && pixel.y() >= bounds_.y &&
         pixel.y() < bounds_.y + bounds_.height;
}

cv::Mat PinholeCamera::K() const {
  return (cv::Mat_<double>(3, 3) << fx_, 0, cx_, 0, fy_, cy_, 0, 0, 1);
}

bool PinholeCamera::has_distortion() const {
  return std::any_of(calibration_.distortion.begin(), calibration_.distortion.end(),
                     [](double d) { return d != 0.0; });
}

std::vector<cv::Point2f> PinholeCamera::undistort(const std::vector<cv::Point2f>& pixels) const {
  if (pixels.empty() || !has_distortion()) return pixels;
  std::vector<cv::Point2f> out;
  const cv::Mat K = this->K();
  const cv::Mat D = distortion_coefficients(calibration_);
  if (calibration_.model == CameraModel::KannalaBrandt8) {
    cv::fisheye::undistortPoints(pixels, out, K, D, cv::noArray(), K);
  } else {
    // More iterations than cv::undistortPoints' fixed 5: strong radial
    // distortion (e.g. TUM fr1) leaves ~0.1 px error at the corners otherwise.
    cv::undistortPoints(pixels, out, K, D, cv::noArray(), K, undistort_criteria());
  }
  return out;
}

std::vector<cv::KeyPoint> PinholeCamera::undistort(const std::vector<cv::KeyPoint>& keypoints) const {
  if (keypoints.empty() || !has_distortion()) return keypoints;
  std::vector<cv::Point2f> pts(keypoints.size());
  for (std::size_t i = 0; i < keypoints.size(); ++i) pts[i] = keypoints[i].pt;
  const auto und = undistort(pts);
  std::vector<cv::KeyPoint> out = keypoints;
  for (std::size_t i = 0; i < out.size(); ++i) out[i].pt = und[i];
  return out;
}

}  // namespace stillslam
