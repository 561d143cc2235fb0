#include <gtest/gtest.h>

#include "geometry/synthetic_scene.h"
#include "stillslam/optimize/pose_optimizer.h"

namespace stillslam {
namespace {

struct PoseScene {
  std::vector<PoseObservation> observations;
  std::vector<bool> is_outlier;
};

// ~n observations of points in front of the camera; every third is stereo
// (when stereo is set), `outlier_ratio` of them get a random pixel.
PoseScene make_scene(const PinholeCamera& cam, const Eigen::Isometry3d& T, int n, double outlier_ratio, bool stereo,
                     unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> ux(0, 640), uy(0, 480), coin(0, 1);
  std::uniform_int_distribution<int> level(0, 1);
  PoseScene s;
  while (static_cast<int>(s.observations.size()) < n) {
    const Eigen::Vector3d p = testing::random_points(rng, 1)[0];
    const Eigen::Vector3d pc = T * p;
    const Eigen::Vector2d uv = cam.project(pc);
    if (pc.z() <= 0.1 || !cam.in_image(uv)) continue;
    PoseObservation o;
    o.point_world = p;
    const int lvl = level(rng);
    const double sigma = std::pow(1.2, lvl);
    o.inv_sigma2 = 1.0 / (sigma * sigma);
    const bool out = coin(rng) < outlier_ratio;
    o.pixel = out ? Eigen::Vector2d(ux(rng), uy(rng)) : Eigen::Vector2d(uv + sigma * Eigen::Vector2d(noise(rng), noise(rng)));
    if (stereo && s.observations.size() % 3 != 0) {
      o.u_right = out ? o.pixel.x() - 40.0 * coin(rng) : cam.project_right_u(pc) + sigma * noise(rng);
    }
    s.observations.push_back(o);
    s.is_outlier.push_back(out);
  }
  return s;
}

Eigen::Isometry3d perturb(const Eigen::Isometry3d& T, double meters, double degrees) {
  Vector6d xi;
  xi << 0.6, -0.8, 0.0, 0.0, 0.6, -0.8;  // unit rotation axis, unit translation direction
  xi.head<3>() *= degrees * M_PI / 180.0;
  xi.tail<3>() *= meters;
  Eigen::Isometry3d D = Eigen::Isometry3d::Identity();
  D.linear() = so3_exp(xi.head<3>());
  D.translation() = xi.tail<3>();
  return D * T;
}

void expect_recovers_pose(bool stereo) {
  const PinholeCamera cam(testing::tum_like_calibration(), 40.0);
  const Eigen::Isometry3d T_true = testing::camera_pose({0.1, 0.2, -0.3}, {0.02, -0.05, 0.1});
  const PoseScene s = make_scene(cam, T_true, 500, 0.3, stereo, stereo ? 21 : 22);
  const Eigen::Isometry3d T0 = perturb(T_true, 0.10, 5.0);
  ASSERT_GT(testing::translation_error(T0, T_true), 0.09);
  const PoseOptimizationResult r = optimize_pose(cam, T0, s.observations);
  // Oracle: least squares on the true inliers only, no robust loss — the
  // accuracy the noise allows. The robust rounds must come close to it.
  std::vector<PoseObservation> good;
  for (std::size_t i = 0; i < s.observations.size(); ++i) {
    if (!s.is_outlier[i]) good.push_back(s.observations[i]);
  }
  PoseOptimizerOptions oracle_options;
  oracle_options.rounds = 1;
  oracle_options.huber = false;
  const PoseOptimizationResult oracle = optimize_pose(cam, T0, good, oracle_options);
  const double err = testing::translation_error(r.T_cam_world, T_true);
  EXPECT_LT(err, stereo ? 0.003 : 0.006);
  EXPECT_LT(err, 1.5 * testing::translation_error(oracle.T_cam_world, T_true) + 0.001);
  EXPECT_LT(testing::rotation_error_deg(r.T_cam_world, T_true), 0.1);
  int correct = 0, outliers = 0, inliers = 0;
  for (std::size_t i = 0; i < s.observations.size(); ++i) {
    correct += r.inlier[i] == !s.is_outlier[i];
    outliers += s.is_outlier[i];
    inliers += r.inlier[i];
  }
  EXPECT_GT(outliers, 120);
  EXPECT_GT(correct, 0.95 * s.observations.size());
  EXPECT_EQ(inliers, r.num_inliers);
}

TEST(PoseOptimizer, RecoversPoseMonoWith30PercentOutliers) { expect_recovers_pose(false); }
TEST(PoseOptimizer, RecoversPoseStereoWith30PercentOutliers) { expect_recovers_pose(true); }

TEST(PoseOptimizer, NoiselessIsExactAndEmptyIsIdentity) {
  const PinholeCamera cam(testing::tum_like_calibration(), 40.0);
  const Eigen::Isometry3d T_true = testing::camera_pose({0.1, 0.2, -0.3}, {0.02, -0.05, 0.1});
  PoseScene s = make_scene(cam, T_true, 100, 0.0, true, 23);
  const Eigen::Isometry3d T0 = perturb(T_true, 0.05, 2.0);
  for (std::size_t i = 0; i < s.observations.size(); ++i) {
    const Eigen::Vector3d pc = T_true * s.observations[i].point_world;
    s.observations[i].pixel = cam.project(pc);
    if (s.observations[i].u_right >= 0) s.observations[i].u_right = cam.project_right_u(pc);
  }
  const PoseOptimizationResult r = optimize_pose(cam, T0, s.observations);
  EXPECT_LT(testing::translation_error(r.T_cam_world, T_true), 1e-7);
  EXPECT_EQ(r.num_inliers, 100);
  const PoseOptimizationResult e = optimize_pose(cam, T0, {});
  EXPECT_TRUE(e.T_cam_world.isApprox(T0));
  EXPECT_EQ(e.num_inliers, 0);
}

TEST(PoseOptimizer, PointsBehindCameraAreOutliers) {
  const PinholeCamera cam(testing::tum_like_calibration());
  const Eigen::Isometry3d T_true = testing::camera_pose({0, 0, 0}, {0, 0, 0});
  PoseScene s = make_scene(cam, T_true, 60, 0.0, false, 24);
  PoseObservation behind;
  behind.point_world = {0.1, 0.1, -2.0};
  behind.pixel = {300, 200};
  s.observations.push_back(behind);
  // And one exactly in the camera plane (depth 0 cannot be projected).
  PoseObservation at_zero = behind;
  at_zero.point_world = {0.5, 0.1, 0.0};
  s.observations.push_back(at_zero);
  const PoseOptimizationResult r = optimize_pose(cam, T_true, s.observations);
  EXPECT_FALSE(r.inlier[r.inlier.size() - 2]);
  EXPECT_FALSE(r.inlier.back());
  EXPECT_GE(r.num_inliers, 55);  // 60 noisy inliers, a few beyond the 95% chi2 gate
  EXPECT_LE(r.num_inliers, 60);
  EXPECT_LT(testing::translation_error(r.T_cam_world, T_true), 0.01);
}

}  // namespace
}  // namespace stillslam
