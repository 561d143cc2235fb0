#include <gtest/gtest.h>

#include "geometry/synthetic_scene.h"
#include "stillslam/optimize/pose_residuals.h"

namespace stillslam {
namespace {

// Four observations: mono and stereo, each once near (inside the Huber
// region) and once far off (in the linear region).
struct Fixture {
  PinholeCamera cam{testing::tum_like_calibration(), 40.0};
  Intrinsics k{cam};
  Eigen::Isometry3d anchor = testing::camera_pose({0.2, -0.1, 0.3}, {0.1, -0.2, 0.05});
  std::vector<PoseObservation> obs;
  std::vector<bool> stereo{false, true, false, true};
  Fixture() {
    const std::vector<Eigen::Vector3d> pts = {{0.4, -0.3, 3.5}, {-0.5, 0.2, 2.5}, {0.1, 0.6, 4.0}, {0.9, 0.1, 5.0}};
    const std::vector<double> offset = {0.5, 0.7, 15.0, -12.0};
    for (std::size_t i = 0; i < pts.size(); ++i) {
      PoseObservation o;
      o.point_world = pts[i];
      const Eigen::Vector3d pc = anchor * pts[i];
      o.pixel = cam.project(pc) + Eigen::Vector2d(offset[i], -0.5 * offset[i]);
      if (stereo[i]) o.u_right = cam.project_right_u(pc) + 0.3 * offset[i];
      o.inv_sigma2 = 1.0 / (1.2 * 1.2);
      obs.push_back(o);
    }
  }
};

void expect_jacobian_matches(bool robust) {
  const Fixture f;
  PoseResidualsOptions options;
  options.robust = robust;
  const PoseResiduals cost(f.k, f.anchor, f.obs, f.stereo, {0, 1, 2, 3}, options);
  ASSERT_EQ(cost.num_residuals(), 10);
  // Away from delta = 0 so the SO3 left Jacobian matters.
  const double delta[6] = {0.03, -0.05, 0.02, 0.01, 0.02, -0.03};
  Eigen::Matrix<double, 10, 1> r;
  Eigen::Matrix<double, 10, 6, Eigen::RowMajor> J;
  const double* params[1] = {delta};
  double* jac[1] = {J.data()};
  ASSERT_TRUE(cost.Evaluate(params, r.data(), jac));
  Eigen::Matrix<double, 10, 6> N;
  for (int c = 0; c < 6; ++c) {
    double plus[6], minus[6];
    std::copy(delta, delta + 6, plus);
    std::copy(delta, delta + 6, minus);
    plus[c] += 1e-6;
    minus[c] -= 1e-6;
    Eigen::Matrix<double, 10, 1> rp, rm;
    const double* pp[1] = {plus};
    const double* pm[1] = {minus};
    ASSERT_TRUE(cost.Evaluate(pp, rp.data(), nullptr));
    ASSERT_TRUE(cost.Evaluate(pm, rm.data(), nullptr));
    N.col(c) = (rp - rm) / 2e-6;
  }
  EXPECT_LT((J - N).norm(), 1e-5 * N.norm());
}

TEST(PoseResiduals, JacobianMatchesNumericDifferences) { expect_jacobian_matches(false); }
TEST(PoseResiduals, RobustJacobianMatchesNumericDifferences) { expect_jacobian_matches(true); }

TEST(PoseResiduals, RobustResidualSquaresToHuberCost) {
  const Fixture f;
  PoseResidualsOptions plain_options, robust_options;
  plain_options.robust = false;
  const PoseResiduals plain(f.k, f.anchor, f.obs, f.stereo, {0, 1, 2, 3}, plain_options);
  const PoseResiduals robust(f.k, f.anchor, f.obs, f.stereo, {0, 1, 2, 3}, robust_options);
  const double delta[6] = {0, 0, 0, 0, 0, 0};
  const double* params[1] = {delta};
  Eigen::Matrix<double, 10, 1> a, b;
  ASSERT_TRUE(plain.Evaluate(params, a.data(), nullptr));
  ASSERT_TRUE(robust.Evaluate(params, b.data(), nullptr));
  const int rows[4] = {2, 3, 2, 3};
  const double huber[4] = {robust_options.huber_mono, robust_options.huber_stereo, robust_options.huber_mono,
                           robust_options.huber_stereo};
  int row = 0;
  for (int i = 0; i < 4; ++i) {
    const double s = a.segment(row, rows[i]).squaredNorm();
    const double d = huber[i];
    const double rho = s <= d * d ? s : 2 * d * std::sqrt(s) - d * d;
    EXPECT_NEAR(b.segment(row, rows[i]).squaredNorm(), rho, 1e-9 * (1 + rho));
    // The first two are inside the quadratic region, the others beyond it.
    EXPECT_EQ(s <= d * d, i < 2);
    row += rows[i];
  }
  // The anchored pose at delta = 0 is the anchor.
  EXPECT_TRUE(robust.pose(delta).isApprox(f.anchor, 1e-12));
}

}  // namespace
}  // namespace stillslam
