// The analytic BA Jacobians against Ceres' automatic differentiation of the
// same residuals written with the left update [Exp(omega), v] * T.
#include <gtest/gtest.h>

#include <ceres/autodiff_cost_function.h>
#include <ceres/rotation.h>

#include "geometry/synthetic_scene.h"
#include "stillslam/optimize/reprojection_costs.h"
#include "stillslam/optimize/se3_manifold.h"

namespace stillslam {
namespace {

// Residual rows of one observation as a function of the tangent delta at the
// pose T_cam_world and of the point: rows 0, 1 left image, row 2 right image.
struct ReprojectionFunctor {
  Intrinsics k;
  Eigen::Isometry3d T_cam_world;
  Eigen::Vector3d observation;  // u, v, u_right
  double sqrt_info;
  int first_row, rows;  // which of the three rows the cost returns (padded with zeros to `rows`)

  template <typename T>
  bool operator()(const T* delta, const T* point, T* residuals) const {
    Eigen::Matrix<T, 3, 1> p = T_cam_world.linear().cast<T>() * Eigen::Map<const Eigen::Matrix<T, 3, 1>>(point) +
                               T_cam_world.translation().cast<T>();
    T rotated[3];
    ceres::AngleAxisRotatePoint(delta, p.data(), rotated);
    for (int i = 0; i < 3; ++i) p[i] = rotated[i] + delta[3 + i];
    const T u = T(k.fx) * p[0] / p[2] + T(k.cx);
    const T all[3] = {u - observation[0], T(k.fy) * p[1] / p[2] + T(k.cy) - observation[1],
                      u - T(k.bf) / p[2] - observation[2]};
    for (int r = 0; r < rows; ++r) {
      const int row = first_row + r;
      residuals[r] = row < 3 ? T(sqrt_info) * all[row] : T(0);
    }
    return true;
  }
};

template <int R>
void expect_same_jacobians(const ceres::CostFunction& analytic, const ReprojectionFunctor& functor,
                           const PoseParams& pose, const Eigen::Vector3d& X) {
  const ceres::AutoDiffCostFunction<ReprojectionFunctor, R, 6, 3> autodiff(new ReprojectionFunctor(functor));
  Eigen::Matrix<double, R, 7, Eigen::RowMajor> J_pose;
  Eigen::Matrix<double, R, 3, Eigen::RowMajor> J_point, A_point;
  Eigen::Matrix<double, R, 6, Eigen::RowMajor> A_pose;
  Eigen::Matrix<double, R, 1> r, a;
  const double* params[2] = {pose.data(), X.data()};
  double* jacobians[2] = {J_pose.data(), J_point.data()};
  ASSERT_TRUE(analytic.Evaluate(params, r.data(), jacobians));
  const double zero[6] = {0, 0, 0, 0, 0, 0};
  const double* auto_params[2] = {zero, X.data()};
  double* auto_jacobians[2] = {A_pose.data(), A_point.data()};
  ASSERT_TRUE(autodiff.Evaluate(auto_params, a.data(), auto_jacobians));
  EXPECT_LT((r - a).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((J_pose.template leftCols<6>() - A_pose).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT(J_pose.col(6).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((J_point - A_point).cwiseAbs().maxCoeff(), 1e-6);
}

class CostAutodiff : public ::testing::Test {
 protected:
  PinholeCamera cam{testing::tum_like_calibration(), 40.0};
  Intrinsics k{cam};
  Eigen::Isometry3d T = testing::camera_pose({0.2, -0.1, 0.3}, {0.1, -0.2, 0.05});
  PoseParams pose = to_pose_params(T);
  Eigen::Vector3d X{0.4, -0.3, 3.5};
  Eigen::Vector3d obs{300.0, 250.0, 290.0};
  double inv_sigma2 = 1.44;
};

TEST_F(CostAutodiff, MonoCostMatchesAutodiff) {
  const MonoBaCost mono(k, obs.head<2>(), inv_sigma2);
  expect_same_jacobians<2>(mono, {k, T, obs, std::sqrt(inv_sigma2), 0, 2}, pose, X);
}

TEST_F(CostAutodiff, StereoCostMatchesAutodiff) {
  const StereoBaCost stereo(k, obs.head<2>(), obs.z(), inv_sigma2);
  expect_same_jacobians<3>(stereo, {k, T, obs, std::sqrt(inv_sigma2), 0, 3}, pose, X);
}

TEST_F(CostAutodiff, RightImageRowMatchesAutodiffAndPadsWithZero) {
  const StereoRightBaCost right(k, obs.z(), inv_sigma2);
  expect_same_jacobians<2>(right, {k, T, obs, std::sqrt(inv_sigma2), 2, 2}, pose, X);
}

}  // namespace
}  // namespace stillslam
