#include "stillslam/io/stereo_rectifier.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "stillslam/core/error.h"

namespace stillslam {
namespace {

cv::Mat camera_matrix(const CameraCalibration& c) {
  return (cv::Mat_<double>(3, 3) << c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
}

cv::Mat distortion(const CameraCalibration& c) {
  cv::Mat d = cv::Mat::zeros(1, 5, CV_64F);
  if (c.distortion.size() > 5) throw Error("stereo rectification: more than 5 distortion coefficients");
  for (std::size_t i = 0; i < c.distortion.size(); ++i) d.at<double>(0, static_cast<int>(i)) = c.distortion[i];
  return d;
}

}  // namespace

StereoRectifier::StereoRectifier(const StereoCalibration& raw, cv::Size size) : size_(size) {
  if (raw.left.model != CameraModel::Pinhole || raw.right.model != CameraModel::Pinhole) {
    throw Error("stereo rectification supports pinhole cameras with radial-tangential distortion only "
                "(KannalaBrandt8 fisheye pairs are not supported yet)");
  }
  if (size.width <= 0 || size.height <= 0) throw Error("stereo rectification: unknown image size");
  if (raw.T_c1_c2.translation().norm() <= 0) throw Error("stereo rectification: zero baseline in T_c1_c2");

  // OpenCV wants the transform taking left-camera points into the right camera.
  const Eigen::Isometry3d T_c2_c1 = raw.T_c1_c2.inverse();
  cv::Mat R(3, 3, CV_64F), t(3, 1, CV_64F);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R.at<double>(r, c) = T_c2_c1.linear()(r, c);
    t.at<double>(r, 0) = T_c2_c1.translation()(r);
  }
  const cv::Mat K1 = camera_matrix(raw.left), K2 = camera_matrix(raw.right);
  const cv::Mat D1 = distortion(raw.left), D2 = distortion(raw.right);
  cv::Mat R1, R2, P1, P2, Q;
  cv::stereoRectify(K1, D1, K2, D2, size, R, t, R1, R2, P1, P2, Q, cv::CALIB_ZERO_DISPARITY, 0.0, size);
  cv::initUndistortRectifyMap(K1, D1, R1, P1, size, CV_32FC1, map_left_x_, map_left_y_);
  cv::initUndistortRectifyMap(K2, D2, R2, P2, size, CV_32FC1, map_right_x_, map_right_y_);
  R1_ = cv::Matx33d(R1);

  CameraCalibration cam;
  cam.fx = P1.at<double>(0, 0);
  cam.fy = P1.at<double>(1, 1);
  cam.cx = P1.at<double>(0, 2);
  cam.cy = P1.at<double>(1, 2);
  cam.width = size.width;
  cam.height = size.height;
  const double baseline = -P2.at<double>(0, 3) / P2.at<double>(0, 0);
  if (!(baseline > 0)) {
    throw Error("stereo rectification: the right camera is not to the right of the left one "
                "(check that T_c1_c2 is camera 2 expressed in camera 1)");
  }
  rectified_.left = cam;
  rectified_.right = cam;
  rectified_.T_c1_c2 = Eigen::Isometry3d::Identity();
  rectified_.T_c1_c2.translation() = Eigen::Vector3d(baseline, 0, 0);
  rectified_.baseline = baseline;
  rectified_.rectified = true;
}

cv::Mat StereoRectifier::rectify_left(const cv::Mat& image) const {
  cv::Mat out;
  cv::remap(image, out, map_left_x_, map_left_y_, cv::INTER_LINEAR);
  return out;
}

cv::Mat StereoRectifier::rectify_right(const cv::Mat& image) const {
  cv::Mat out;
  cv::remap(image, out, map_right_x_, map_right_y_, cv::INTER_LINEAR);
  return out;
}

}  // namespace stillslam
