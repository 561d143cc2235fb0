#include <gtest/gtest.h>

#include "geometry/synthetic_scene.h"
#include "stillslam/geometry/pinhole_camera.h"
#include "stillslam/geometry/triangulation.h"

namespace stillslam {
namespace {

TEST(Triangulation, NoiselessPointsAreExact) {
  const PinholeCamera cam(testing::tum_like_calibration());
  const Eigen::Isometry3d T1 = testing::camera_pose({0, 0, 0}, {0, 0, 0});
  const Eigen::Isometry3d T2 = testing::camera_pose({0.4, 0.05, -0.1}, {0.02, -0.08, 0.01});
  std::mt19937 rng(5);
  int n = 0;
  for (const auto& p : testing::random_points(rng, 300)) {
    const Eigen::Vector3d r1 = cam.normalized(cam.project(T1 * p));
    const Eigen::Vector3d r2 = cam.normalized(cam.project(T2 * p));
    const auto x = triangulate(r1, T1, r2, T2);
    ASSERT_TRUE(x.has_value());
    EXPECT_LT((*x - p).norm(), 1e-9);
    // Unit bearings give the same point.
    const auto y = triangulate(r1.normalized(), T1, r2.normalized() * 3.0, T2);
    ASSERT_TRUE(y.has_value());
    EXPECT_LT((*y - p).norm(), 1e-9);
    ++n;
  }
  EXPECT_EQ(n, 300);
}

TEST(Triangulation, RejectsLowParallaxAndPointsBehind) {
  const Eigen::Isometry3d T1 = testing::camera_pose({0, 0, 0}, {0, 0, 0});
  const Eigen::Isometry3d T2 = testing::camera_pose({0.001, 0, 0}, {0, 0, 0});
  const Eigen::Vector3d p(0.2, 0.1, 5.0);
  auto ray = [](const Eigen::Isometry3d& T, const Eigen::Vector3d& pw) {
    const Eigen::Vector3d c = T * pw;
    return Eigen::Vector3d(c / c.z());
  };
  // 1 mm baseline at 5 m: parallax 0.01 deg.
  EXPECT_FALSE(triangulate(ray(T1, p), T1, ray(T2, p), T2).has_value());
  TriangulationOptions loose;
  loose.max_cos_parallax = 1.0;
  EXPECT_TRUE(triangulate(ray(T1, p), T1, ray(T2, p), T2, loose).has_value());
  // Rays that meet behind the cameras: mirrored observation.
  const Eigen::Isometry3d T3 = testing::camera_pose({1.0, 0, 0}, {0, 0, 0});
  const Eigen::Vector3d q(0.5, 0, -3.0);  // behind both
  const Eigen::Vector3d r1 = -(T1 * q) / (T1 * q).z(), r3 = -(T3 * q) / (T3 * q).z();
  // r1/r3 are the rays through q's projection; the DLT solution is q (z < 0).
  EXPECT_FALSE(triangulate(r1, T1, r3, T3).has_value());
  EXPECT_GT(cos_parallax(p, T1, T2), 0.99999);
}

TEST(Triangulation, DepthFromDisparity) {
  EXPECT_DOUBLE_EQ(*depth_from_disparity(40.0, 320.0, 310.0), 4.0);
  EXPECT_FALSE(depth_from_disparity(40.0, 310.0, 310.0).has_value());
  EXPECT_FALSE(depth_from_disparity(40.0, 300.0, 310.0).has_value());
  EXPECT_FALSE(depth_from_disparity(0.0, 320.0, 310.0).has_value());
}

}  // namespace
}  // namespace stillslam
