#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>

#include "geometry/synthetic_scene.h"
#include "stillslam/core/error.h"
#include "stillslam/geometry/pinhole_camera.h"

namespace stillslam {
namespace {

TEST(PinholeCamera, ProjectUnprojectRoundTrip) {
  const PinholeCamera cam(testing::tum_like_calibration(), 40.0);
  EXPECT_DOUBLE_EQ(cam.baseline(), 40.0 / 517.3);
  std::mt19937 rng(1);
  for (const auto& p : testing::random_points(rng, 200)) {
    const Eigen::Vector2d px = cam.project(p);
    const Eigen::Vector3d back = cam.unproject(px, p.z());
    EXPECT_LT((back - p).norm(), 1e-12);
    // Virtual right coordinate: disparity bf / z.
    EXPECT_NEAR(px.x() - cam.project_right_u(p), 40.0 / p.z(), 1e-12);
  }
  EXPECT_EQ(cam.project({0, 0, 1}), Eigen::Vector2d(318.6, 255.3));
  EXPECT_TRUE(cam.in_image({0, 0}));
  EXPECT_TRUE(cam.in_image({639.5, 479.5}));
  EXPECT_FALSE(cam.in_image({640, 10}));
  EXPECT_FALSE(cam.in_image({-0.1, 10}));
  EXPECT_FALSE(cam.has_distortion());
  EXPECT_EQ(cam.undistorted_bounds(), cv::Rect2f(0, 0, 640, 480));
}

TEST(PinholeCamera, UndistortMatchesOpenCv) {
  CameraCalibration c = testing::tum_like_calibration();
  c.distortion = {0.2624, -0.9531, -0.0054, 0.0026, 1.1633};  // TUM fr1 values
  const PinholeCamera cam(c);
  ASSERT_TRUE(cam.has_distortion());
  std::vector<cv::KeyPoint> kps;
  for (int y = 0; y < 480; y += 37)
    for (int x = 0; x < 640; x += 41) kps.emplace_back(cv::Point2f(float(x), float(y)), 7.f, 33.f, 50.f, 2, 9);
  const auto und = cam.undistort(kps);
  std::vector<cv::Point2f> pts, ref;
  for (const auto& k : kps) pts.push_back(k.pt);
  const cv::Mat D = (cv::Mat_<double>(5, 1) << 0.2624, -0.9531, -0.0054, 0.0026, 1.1633);
  cv::undistortPoints(pts, ref, cam.K(), D, cv::noArray(), cam.K(), PinholeCamera::undistort_criteria());
  ASSERT_EQ(und.size(), kps.size());
  double max_shift = 0;
  for (std::size_t i = 0; i < kps.size(); ++i) {
    EXPECT_FLOAT_EQ(und[i].pt.x, ref[i].x);
    EXPECT_FLOAT_EQ(und[i].pt.y, ref[i].y);
    EXPECT_EQ(und[i].octave, 2);
    EXPECT_EQ(und[i].angle, 33.f);
    max_shift = std::max(max_shift, double(cv::norm(und[i].pt - kps[i].pt)));
  }
  EXPECT_GT(max_shift, 5.0);  // the distortion is strong enough to matter
  // Re-distorting the undistorted points gives the originals back.
  std::vector<cv::Point3f> rays;
  for (const auto& k : und) {
    const Eigen::Vector3d r = cam.normalized({k.pt.x, k.pt.y});
    rays.emplace_back(float(r.x()), float(r.y()), 1.f);
  }
  std::vector<cv::Point2f> redist;
  cv::projectPoints(rays, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), cam.K(), D, redist);
  for (std::size_t i = 0; i < kps.size(); ++i) EXPECT_LT(cv::norm(redist[i] - kps[i].pt), 0.01);
  // Bounds: this barrel-type distortion pushes the corners outwards.
  const cv::Rect2f b = cam.undistorted_bounds();
  EXPECT_NE(b, cv::Rect2f(0, 0, 640, 480));
  EXPECT_GT(b.width, 100.f);
  EXPECT_GT(b.height, 100.f);
}

TEST(PinholeCamera, FisheyeUndistortMatchesOpenCv) {
  CameraCalibration c;
  c.model = CameraModel::KannalaBrandt8;
  c.fx = 190.98;
  c.fy = 190.98;
  c.cx = 254.93;
  c.cy = 256.89;
  c.width = 512;
  c.height = 512;
  c.distortion = {0.0034, 0.0008, -0.0020, 0.0003};
  const PinholeCamera cam(c);
  const std::vector<cv::Point2f> pts = {{10, 20}, {256, 256}, {500, 300}};
  const auto und = cam.undistort(pts);
  std::vector<cv::Point2f> ref;
  cv::fisheye::undistortPoints(pts, ref, cam.K(), cv::Mat(c.distortion), cv::noArray(), cam.K());
  for (std::size_t i = 0; i < pts.size(); ++i) EXPECT_LT(cv::norm(und[i] - ref[i]), 1e-4);
}

TEST(PinholeCamera, RejectsBadCalibration) {
  CameraCalibration c = testing::tum_like_calibration();
  c.fx = 0;
  EXPECT_THROW(PinholeCamera{c}, Error);
  c = testing::tum_like_calibration();
  c.width = 0;
  EXPECT_THROW(PinholeCamera{c}, Error);
  c = testing::tum_like_calibration();
  c.distortion = {0.1, 0.2, 0.3};
  EXPECT_THROW(PinholeCamera{c}, Error);
}

}  // namespace
}  // namespace stillslam
