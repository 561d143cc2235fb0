// The Gaussian pose prior (optimize/pose_prior.h): its residual, its
// automatic Jacobian against finite differences, and optimize_pose pulled
// between the measurements and the prior by its sigma.
#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "geometry/synthetic_scene.h"
#include "stillslam/core/option_check.h"
#include "stillslam/geometry/se3.h"
#include "stillslam/optimize/pose_optimizer.h"
#include "stillslam/optimize/pose_prior.h"

namespace stillslam {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

Vector6d evaluate(const ceres::CostFunction& cost, const Vector6d& delta, Eigen::Matrix<double, 6, 6, Eigen::RowMajor>* J) {
  Vector6d r;
  const double* params[] = {delta.data()};
  double* jacobians[] = {J ? J->data() : nullptr};
  EXPECT_TRUE(cost.Evaluate(params, r.data(), J ? jacobians : nullptr));
  return r;
}

// The pose 2 mm (camera centre) and 0.02 rad away from the mean.
Eigen::Isometry3d mean_pose() { return testing::camera_pose({0.1, -0.2, 0.3}, {0.5, 0.2, -1.0}); }

TEST(PosePrior, ResidualIsTheWhitenedOffsetFromTheMean) {
  PosePrior prior;
  prior.T_cam_world = mean_pose();
  prior.sigma_translation = 0.001;
  prior.sigma_rotation = 0.01;
  // The anchor: the mean's camera moved 2 mm along world x and turned 0.02 rad about camera z.
  Eigen::Isometry3d anchor = prior.T_cam_world;
  anchor.linear() = so3_exp(Eigen::Vector3d(0, 0, 0.02)) * anchor.linear();
  const Eigen::Vector3d centre = camera_centre(prior.T_cam_world) + Eigen::Vector3d(0.002, 0, 0);
  anchor.translation() = -(anchor.linear() * centre);
  const std::unique_ptr<ceres::CostFunction> cost(make_pose_prior_cost(anchor, prior));
  const Vector6d r = evaluate(*cost, Vector6d::Zero(), nullptr);
  EXPECT_NEAR(r[0], 0, 1e-12);
  EXPECT_NEAR(r[1], 0, 1e-12);
  EXPECT_NEAR(r[2], 2.0, 1e-9);  // 0.02 rad / 0.01
  EXPECT_NEAR(r[3], 2.0, 1e-9);  // 2 mm / 1 mm
  EXPECT_NEAR(r[4], 0, 1e-9);
  EXPECT_NEAR(r[5], 0, 1e-9);
  // At the mean itself: zero.
  const std::unique_ptr<ceres::CostFunction> at_mean(make_pose_prior_cost(prior.T_cam_world, prior));
  EXPECT_LT(evaluate(*at_mean, Vector6d::Zero(), nullptr).norm(), 1e-12);
  // A dead zone of 1.5 mm leaves 0.5 mm of the 2 mm.
  prior.dead_zone = 0.0015;
  const std::unique_ptr<ceres::CostFunction> dead(make_pose_prior_cost(anchor, prior));
  EXPECT_NEAR(evaluate(*dead, Vector6d::Zero(), nullptr)[3], 0.5, 1e-9);
  prior.dead_zone = 0.003;
  const std::unique_ptr<ceres::CostFunction> inside(make_pose_prior_cost(anchor, prior));
  EXPECT_NEAR(evaluate(*inside, Vector6d::Zero(), nullptr).tail<3>().norm(), 0, 1e-12);
}

TEST(PosePrior, JacobianMatchesFiniteDifferences) {
  PosePrior prior;
  prior.T_cam_world = mean_pose();
  prior.dead_zone = 0.001;
  Eigen::Isometry3d anchor = prior.T_cam_world;
  anchor.linear() = so3_exp(Eigen::Vector3d(0.01, -0.02, 0.03)) * anchor.linear();
  anchor.translation() += Eigen::Vector3d(0.01, 0.02, -0.005);
  const std::unique_ptr<ceres::CostFunction> cost(make_pose_prior_cost(anchor, prior));
  Vector6d delta;
  delta << 0.003, -0.001, 0.002, 0.004, -0.002, 0.001;
  Eigen::Matrix<double, 6, 6, Eigen::RowMajor> J;
  evaluate(*cost, delta, &J);
  const double h = 1e-7;
  for (int c = 0; c < 6; ++c) {
    Vector6d plus = delta, minus = delta;
    plus[c] += h;
    minus[c] -= h;
    const Vector6d numeric = (evaluate(*cost, plus, nullptr) - evaluate(*cost, minus, nullptr)) / (2 * h);
    EXPECT_LT((J.col(c) - numeric).norm(), 1e-4 * (1 + numeric.norm())) << "column " << c;
  }
  EXPECT_GT(J.norm(), 100);  // whitened by 1 mm and 0.01 rad: not a zero Jacobian
}

// A few far points fix the pose; the prior 5 cm away pulls it in proportion to its weight.
TEST(PosePrior, OptimizePoseMovesTowardsThePriorWithItsWeight) {
  const PinholeCamera cam(testing::tum_like_calibration(), 40.0);
  const Eigen::Isometry3d T_true = testing::camera_pose({0.1, 0.2, -0.3}, {0.02, -0.05, 0.1});
  std::mt19937 rng(3);
  std::vector<PoseObservation> observations;
  for (const Eigen::Vector3d& p : testing::random_points(rng, 400)) {
    const Eigen::Vector3d pc = T_true * p;
    if (pc.z() <= 0.1 || !cam.in_image(cam.project(pc))) continue;
    PoseObservation o;
    o.point_world = p;
    o.pixel = cam.project(pc);
    o.u_right = cam.project_right_u(pc);
    observations.push_back(o);
  }
  ASSERT_GT(observations.size(), 50u);
  PosePrior prior;
  prior.T_cam_world = T_true;
  prior.T_cam_world.translation() += Eigen::Vector3d(0.05, 0, 0);
  const Eigen::Vector3d true_centre = camera_centre(T_true), prior_centre = camera_centre(prior.T_cam_world);
  auto centre_with = [&](double sigma) {
    prior.sigma_translation = sigma;
    return camera_centre(optimize_pose(cam, T_true, observations, {}, &prior).T_cam_world);
  };
  const double none = (camera_centre(optimize_pose(cam, T_true, observations).T_cam_world) - true_centre).norm();
  const double loose = (centre_with(10.0) - true_centre).norm();
  const double tight = (centre_with(1e-7) - prior_centre).norm();
  const Eigen::Vector3d middle = centre_with(0.002);
  std::printf("no prior %.2e m, sigma 10 m %.2e m from the truth; sigma 1e-7 %.2e m from the prior; "
              "sigma 2 mm %.4f m from the truth, %.4f m from the prior\n",
              none, loose, tight, (middle - true_centre).norm(), (middle - prior_centre).norm());
  EXPECT_LT(none, 1e-8);
  EXPECT_LT(loose, 1e-5);
  EXPECT_LT(tight, 1e-4);
  EXPECT_GT((middle - true_centre).norm(), 1e-4);
  EXPECT_GT((middle - prior_centre).norm(), 1e-4);
}

TEST(PosePrior, OptionsAreChecked) {
  PosePrior prior;
  prior.check();
  prior.sigma_translation = 0;
  EXPECT_THROW(prior.check(), OptionError);
  prior = {};
  prior.sigma_rotation = -1;
  EXPECT_THROW(prior.check(), OptionError);
  prior = {};
  prior.dead_zone = -0.001;
  EXPECT_THROW(prior.check(), OptionError);
  EXPECT_THROW(make_pose_prior_cost(Eigen::Isometry3d::Identity(), prior), OptionError);
}

}  // namespace
}  // namespace stillslam
