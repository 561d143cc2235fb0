#include <gtest/gtest.h>

#include "geometry/synthetic_scene.h"
#include "stillslam/core/error.h"
#include "stillslam/geometry/pnp.h"

namespace stillslam {
namespace {

TEST(Pnp, RansacRecoversPoseWith30PercentOutliers) {
  const PinholeCamera cam(testing::tum_like_calibration());
  const Eigen::Isometry3d T_true = testing::camera_pose({0.3, -0.2, 0.1}, {0.05, 0.1, -0.03});
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.5);
  std::uniform_real_distribution<double> ux(0, 640), uy(0, 480);
  std::vector<Eigen::Vector3d> pts;
  std::vector<Eigen::Vector2d> px;
  std::vector<bool> is_outlier;
  for (const auto& p : testing::random_points(rng, 400)) {
    const Eigen::Vector2d uv = cam.project(T_true * p);
    if (!cam.in_image(uv)) continue;
    const bool out = pts.size() % 10 < 3;
    pts.push_back(p);
    px.push_back(out ? Eigen::Vector2d(ux(rng), uy(rng)) : Eigen::Vector2d(uv + Eigen::Vector2d(noise(rng), noise(rng))));
    is_outlier.push_back(out);
  }
  ASSERT_GT(pts.size(), 200u);
  const PnpResult r = solve_pnp_ransac(cam, pts, px);
  ASSERT_TRUE(r.success);
  EXPECT_LT(testing::translation_error(r.T_cam_world, T_true), 1e-3);
  EXPECT_LT(testing::rotation_error_deg(r.T_cam_world, T_true), 0.05);
  int correct = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) correct += r.inlier[i] == !is_outlier[i];
  EXPECT_GT(correct, int(0.97 * pts.size()));
  EXPECT_GT(r.num_inliers, int(0.65 * pts.size()));
}

TEST(Pnp, FailsCleanlyOnTooFewPoints) {
  const PinholeCamera cam(testing::tum_like_calibration());
  EXPECT_FALSE(solve_pnp_ransac(cam, {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, {{0, 0}, {1, 1}, {2, 2}}).success);
  EXPECT_THROW(solve_pnp_ransac(cam, {{0, 0, 1}}, {}), Error);
}

TEST(Alignment, UmeyamaExactWithScale) {
  const Sim3 S(1.7, so3_exp({0.3, -0.2, 0.9}), {0.5, -1, 2});
  std::mt19937 rng(12);
  const auto src = testing::random_points(rng, 50);
  std::vector<Eigen::Vector3d> dst;
  for (const auto& p : src) dst.push_back(S * p);
  const Sim3 est = align_umeyama(src, dst, true);
  EXPECT_NEAR(est.s, 1.7, 1e-9);
  EXPECT_LT((est.matrix() - S.matrix()).norm(), 1e-9);
  const Sim3 rigid = align_umeyama(src, dst, false);
  EXPECT_DOUBLE_EQ(rigid.s, 1.0);
  EXPECT_THROW(align_umeyama(src, {}, false), Error);
}

TEST(Alignment, RansacRejects40PercentOutliers) {
  const Eigen::Isometry3d T = testing::camera_pose({1, 2, -0.5}, {0.2, -0.4, 1.0});
  std::mt19937 rng(13);
  std::normal_distribution<double> noise(0.0, 0.005);
  std::uniform_real_distribution<double> junk(-3, 3);
  const auto src = testing::random_points(rng, 200);
  std::vector<Eigen::Vector3d> dst;
  std::vector<bool> is_outlier;
  for (std::size_t i = 0; i < src.size(); ++i) {
    const bool out = i % 5 < 2;
    dst.push_back(out ? Eigen::Vector3d(junk(rng), junk(rng), junk(rng))
                      : Eigen::Vector3d(T * src[i] + Eigen::Vector3d(noise(rng), noise(rng), noise(rng))));
    is_outlier.push_back(out);
  }
  const AlignmentResult r = align_ransac(src, dst);
  ASSERT_TRUE(r.success);
  EXPECT_LT((r.S_dst_src.t - T.translation()).norm(), 5e-3);
  EXPECT_LT(rotation_angle(r.S_dst_src.R * T.linear().transpose()) * 180 / M_PI, 0.2);
  int correct = 0;
  for (std::size_t i = 0; i < src.size(); ++i) correct += r.inlier[i] == !is_outlier[i];
  EXPECT_GE(correct, 198);
  // With scale: a scaled copy is recovered.
  std::vector<Eigen::Vector3d> scaled;
  for (const auto& p : dst) scaled.push_back(0.5 * p);
  AlignmentRansacOptions o;
  o.with_scale = true;
  o.max_error = 0.025;
  const AlignmentResult rs = align_ransac(src, scaled, o);
  ASSERT_TRUE(rs.success);
  EXPECT_NEAR(rs.S_dst_src.s, 0.5, 2e-3);
}

}  // namespace
}  // namespace stillslam
