// Geometry of the ray caster: exact depth, correct texture lookup across
// views, and masks that follow the cut-out's alpha.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "stillslam/sim/renderer.h"

namespace stillslam::sim {
namespace {

CameraCalibration test_camera() {
  return pinhole_calibration(200, 210, 79.5, 61.0, 160, 120);
}

// Texture whose colour encodes its own coordinates: B = 255 x, G = 255 y.
cv::Mat coordinate_texture() {
  cv::Mat t(256, 256, CV_8UC3);
  for (int y = 0; y < 256; ++y) {
    for (int x = 0; x < 256; ++x) t.at<cv::Vec3b>(y, x) = cv::Vec3b(x, y, 128);
  }
  return t;
}

// A quad centred on `centre`, spanning `u` and `v` (visible side: u right, v down).
Quad centred_quad(const Eigen::Vector3d& centre, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                  int texture) {
  Quad q;
  q.origin = centre - u / 2 - v / 2;
  q.axis_u = u;
  q.axis_v = v;
  q.texture = texture;
  return q;
}

TEST(Renderer, DepthOfATiltedPlaneIsExact) {
  std::vector<MipTexture> tex{MipTexture(coordinate_texture())};
  const Renderer renderer(test_camera(), std::move(tex));
  // Plane through (0.1, -0.05, 2.5), tilted 35 deg about y and 10 deg about x.
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.61, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(0.17, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  const Eigen::Vector3d centre(0.1, -0.05, 2.5);
  const Quad q = centred_quad(centre, R * Eigen::Vector3d(6, 0, 0), R * Eigen::Vector3d(0, 6, 0), 0);
  const Eigen::Vector3d n = q.axis_u.cross(q.axis_v).normalized();
  // Camera moved and rotated: depth is along its own optical axis.
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();
  T_world_cam.linear() = Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitX()).toRotationMatrix();
  T_world_cam.translation() = Eigen::Vector3d(0.02, 0.03, -0.1);
  const RenderedView view = renderer.render({q}, T_world_cam, 2);
  const CameraCalibration cam = test_camera();
  double max_err = 0;
  int valid = 0;
  for (int v = 0; v < cam.height; ++v) {
    for (int u = 0; u < cam.width; ++u) {
      const Eigen::Vector3d r_cam((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0);
      const Eigen::Vector3d r_world = T_world_cam.linear() * r_cam;
      const double z = n.dot(centre - T_world_cam.translation()) / n.dot(r_world);
      max_err = std::max(max_err, std::abs(z - view.depth.at<float>(v, u)));
      valid += view.depth.at<float>(v, u) > 0;
    }
  }
  EXPECT_EQ(valid, cam.width * cam.height);
  EXPECT_LT(max_err, 1e-3);  // 1 mm
  EXPECT_EQ(cv::countNonZero(view.mask()), 0);
}

TEST(Renderer, ReprojectedPixelsSeeTheSameTextureCoordinate) {
  std::vector<MipTexture> tex{MipTexture(coordinate_texture())};
  const Renderer renderer(test_camera(), std::move(tex));
  // 3.6 m square plane 3 m away, slightly slanted so depth varies across the image.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Quad q = centred_quad({0, 0, 3}, R * Eigen::Vector3d(3.6, 0, 0), R * Eigen::Vector3d(0, 3.6, 0), 0);
  const Eigen::Isometry3d T1 = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T2 = Eigen::Isometry3d::Identity();
  T2.linear() = Eigen::AngleAxisd(-0.08, Eigen::Vector3d::UnitY()).toRotationMatrix();
  T2.translation() = Eigen::Vector3d(0.25, -0.05, 0.2);
  const RenderedView a = renderer.render({q}, T1, 2);
  const RenderedView b = renderer.render({q}, T2, 2);
  const CameraCalibration cam = test_camera();
  int checked = 0;
  double max_diff = 0;
  for (int v = 10; v < cam.height - 10; v += 7) {
    for (int u = 10; u < cam.width - 10; u += 7) {
      const float z = a.depth.at<float>(v, u);
      ASSERT_GT(z, 0);
      const Eigen::Vector3d p1(z * (u - cam.cx) / cam.fx, z * (v - cam.cy) / cam.fy, z);
      const Eigen::Vector3d p2 = T2.inverse() * (T1 * p1);
      const double u2 = cam.fx * p2.x() / p2.z() + cam.cx, v2 = cam.fy * p2.y() / p2.z() + cam.cy;
      if (u2 < 2 || v2 < 2 || u2 > cam.width - 3 || v2 > cam.height - 3) continue;
      cv::Mat patch;
      cv::getRectSubPix(b.bgr, {1, 1}, cv::Point2f(static_cast<float>(u2), static_cast<float>(v2)), patch);
      const cv::Vec3f cb = patch.at<cv::Vec3f>(0, 0), ca = a.bgr.at<cv::Vec3f>(v, u);
      max_diff = std::max({max_diff, std::abs(double(ca[0] - cb[0])), std::abs(double(ca[1] - cb[1]))});
      // And the depth of the reprojected point matches the second view's depth.
      EXPECT_NEAR(p2.z(), b.depth.at<float>(cvRound(v2), cvRound(u2)), 0.02);
      ++checked;
    }
  }
  EXPECT_GT(checked, 150);
  // The texture spans 256 levels over 3.6 m: 1 level ~ 1.4 cm on the plane, ~1 px here.
  EXPECT_LT(max_diff, 1.5);
}

TEST(Renderer, MaskIsTheBillboardAlphaRegion) {
  // An ellipse cut-out (semi-axes 0.45 x 0.9 of the billboard) 2 m away.
  cv::Mat cut(400, 200, CV_8UC4, cv::Scalar(40, 90, 200, 0));
  cv::ellipse(cut, cv::Point(100, 200), cv::Size(90, 180), 0, 0, 360, cv::Scalar(40, 90, 200, 255), -1,
              cv::LINE_AA);
  cv::Mat wall(64, 64, CV_8UC3, cv::Scalar(10, 10, 10));
  std::vector<MipTexture> tex{MipTexture(wall), MipTexture(cut)};
  const Renderer renderer(test_camera(), std::move(tex));
  Quad back = centred_quad({0, 0, 5}, {10, 0, 0}, {0, 10, 0}, 0);
  Quad person = centred_quad({0.05, 0.02, 2}, {0.4, 0, 0}, {0, 0.8, 0}, 1);
  person.alpha_tested = true;
  person.dynamic_id = 7;
  const RenderedView view = renderer.render({back, person}, Eigen::Isometry3d::Identity(), 2);
  const cv::Mat mask = view.mask();
  const CameraCalibration cam = test_camera();
  // Projected ellipse area: pi * (0.18 m * fx / z) * (0.36 m * fy / z).
  const double expected = M_PI * (0.18 * cam.fx / 2) * (0.36 * cam.fy / 2);
  EXPECT_NEAR(cv::countNonZero(mask), expected, 0.02 * expected);
  for (int v = 0; v < cam.height; ++v) {
    for (int u = 0; u < cam.width; ++u) {
      const bool on = mask.at<uchar>(v, u) != 0;
      EXPECT_NEAR(view.depth.at<float>(v, u), on ? 2.0 : 5.0, 1e-4);
      EXPECT_EQ(view.dynamic_ids.at<std::uint16_t>(v, u), on ? 7 : 0);
      // Analytic inside test at the pixel centre (away from the outline).
      const double x = (u - cam.cx) / cam.fx * 2 - 0.05, y = (v - cam.cy) / cam.fy * 2 - 0.02;
      const double r = std::hypot(x / 0.18, y / 0.36);
      if (r < 0.97) {
        EXPECT_TRUE(on) << u << "," << v;
      }
      if (r > 1.03) {
        EXPECT_FALSE(on) << u << "," << v;
      }
    }
  }
}

TEST(Renderer, BackFacesAreNotDrawn) {
  std::vector<MipTexture> tex{MipTexture(coordinate_texture())};
  const Renderer renderer(test_camera(), std::move(tex));
  // Same quad with u and v swapped: its normal points at the camera.
  Quad q = centred_quad({0, 0, 2}, {0, 2, 0}, {2, 0, 0}, 0);
  EXPECT_EQ(cv::countNonZero(renderer.render({q}, Eigen::Isometry3d::Identity(), 1).depth), 0);
}

}  // namespace
}  // namespace stillslam::sim
