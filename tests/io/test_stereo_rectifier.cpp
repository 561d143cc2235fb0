#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>

#include "stillslam/core/error.h"
#include "stillslam/io/stereo_rectifier.h"

namespace stillslam {
namespace {

// EuRoC cam0/cam1 (pinhole, radial-tangential).
StereoCalibration euroc_pair() {
  StereoCalibration s;
  s.left = {CameraModel::Pinhole, 458.654, 457.296, 367.215, 248.375,
            {-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05}, 752, 480};
  s.right = {CameraModel::Pinhole, 457.587, 456.134, 379.999, 255.238,
             {-0.28368365, 0.07451284, -0.00010473, -3.55590700e-05}, 752, 480};
  Eigen::Matrix3d R;
  R << 0.999997256477, -0.002317135723, -0.000343393121, 0.002312067192, 0.999898048507, -0.014090668453,
      0.000376008102, 0.014089835847, 0.999900662638;
  s.T_c1_c2.linear() = R;
  s.T_c1_c2.translation() = Eigen::Vector3d(0.110074137800, -0.000156612054, 0.000889382785);
  return s;
}

// TUM-VI style fisheye pair (KannalaBrandt8).
StereoCalibration fisheye_pair() {
  StereoCalibration s;
  s.left = {CameraModel::KannalaBrandt8, 190.978477, 190.973307, 254.931706, 256.897443,
            {0.003482389, 0.000715034, -0.002053236, 0.000202936}, 512, 512};
  s.right = {CameraModel::KannalaBrandt8, 190.442369, 190.434438, 252.599497, 254.917230,
             {0.003400317, 0.001766278, -0.002663125, 0.000329951}, 512, 512};
  Eigen::Matrix3d R;
  R << 0.999994, 0.00106, -0.00332, -0.00107, 0.999993, -0.00358, 0.00332, 0.00358, 0.999988;
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  s.T_c1_c2.linear() = svd.matrixU() * svd.matrixV().transpose();  // exact rotation
  s.T_c1_c2.translation() = Eigen::Vector3d(0.101, -0.0019, 0.0006);
  return s;
}

cv::Point2d project(const CameraCalibration& c, const Eigen::Vector3d& X) {
  const cv::Mat K = (cv::Mat_<double>(3, 3) << c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
  const std::vector<cv::Point3d> points{{X.x(), X.y(), X.z()}};
  std::vector<cv::Point2d> pixels;
  if (c.model == CameraModel::KannalaBrandt8) {
    cv::fisheye::projectPoints(points, pixels, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, c.distortion);
  } else {
    cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, c.distortion, pixels);
  }
  return pixels.front();
}

// A 3D point seen by both raw cameras lands on the same rectified row in
// both images, with disparity fx * baseline / depth in the rectified frame.
void check_epipolar_geometry(const StereoCalibration& raw) {
  const StereoRectifier rectifier(raw, cv::Size(raw.left.width, raw.left.height));
  const StereoCalibration& rect = rectifier.rectified();
  Eigen::Matrix3d R1;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R1(r, c) = rectifier.left_rotation()(r, c);
  }
  int checked = 0;
  for (double x : {-0.8, -0.3, 0.0, 0.4, 0.9}) {
    for (double y : {-0.5, 0.0, 0.6}) {
      for (double z : {1.5, 4.0, 12.0}) {
        const Eigen::Vector3d X_c1(x * z / 2, y * z / 2, z);
        const Eigen::Vector3d X_c2 = raw.T_c1_c2.inverse() * X_c1;
        const cv::Point2d left = rectifier.rectify_left_point(project(raw.left, X_c1));
        const cv::Point2d right = rectifier.rectify_right_point(project(raw.right, X_c2));
        const double depth = (R1 * X_c1).z();
        EXPECT_NEAR(left.y, right.y, 2e-3) << X_c1.transpose();
        EXPECT_NEAR(left.x - right.x, rect.left.fx * rect.baseline / depth, 2e-3) << X_c1.transpose();
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 45);
}

TEST(StereoRectifier, PinholeEpipolarGeometry) {
  const StereoCalibration raw = euroc_pair();
  check_epipolar_geometry(raw);
  const StereoRectifier rectifier(raw, cv::Size(752, 480));
  EXPECT_NEAR(rectifier.rectified().baseline, 0.1100778, 1e-6);
  EXPECT_TRUE(rectifier.rectified().left.distortion.empty());
}

TEST(StereoRectifier, FisheyeEpipolarGeometry) {
  const StereoCalibration raw = fisheye_pair();
  check_epipolar_geometry(raw);
  const StereoRectifier rectifier(raw, cv::Size(512, 512));
  EXPECT_NEAR(rectifier.rectified().baseline, raw.T_c1_c2.translation().norm(), 1e-9);
}

TEST(StereoRectifier, RejectsBadGeometry) {
  StereoCalibration raw = euroc_pair();
  EXPECT_THROW(StereoRectifier(raw, cv::Size(0, 0)), Error);
  raw.T_c1_c2.translation() = Eigen::Vector3d(-0.11, 0, 0);  // right camera on the left
  EXPECT_THROW(StereoRectifier(raw, cv::Size(752, 480)), Error);
  raw = euroc_pair();
  raw.right.model = CameraModel::KannalaBrandt8;
  EXPECT_THROW(StereoRectifier(raw, cv::Size(752, 480)), Error);
}

}  // namespace
}  // namespace stillslam
