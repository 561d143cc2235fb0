#include <gtest/gtest.h>

#include "geometry/synthetic_scene.h"
#include "stillslam/geometry/se3.h"
#include "stillslam/optimize/reprojection_costs.h"
#include "stillslam/optimize/se3_manifold.h"

namespace stillslam {
namespace {

// Central differences through the manifold's Plus (pose) and plain addition (point).
template <int R>
void numeric_jacobians(const ceres::CostFunction& cost, PoseParams pose, Eigen::Vector3d point,
                       Eigen::Matrix<double, R, 6>& J_pose, Eigen::Matrix<double, R, 3>& J_point, bool has_point) {
  const Se3LeftManifold m;
  const double h = 1e-6;
  auto eval = [&](const PoseParams& p, const Eigen::Vector3d& x) {
    Eigen::Matrix<double, R, 1> r;
    const double* params[2] = {p.data(), x.data()};
    EXPECT_TRUE(cost.Evaluate(params, r.data(), nullptr));
    return r;
  };
  for (int k = 0; k < 6; ++k) {
    double d[6] = {0, 0, 0, 0, 0, 0};
    PoseParams plus, minus;
    d[k] = h;
    m.Plus(pose.data(), d, plus.data());
    d[k] = -h;
    m.Plus(pose.data(), d, minus.data());
    J_pose.col(k) = (eval(plus, point) - eval(minus, point)) / (2 * h);
  }
  if (!has_point) return;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d a = point, b = point;
    a[k] += h;
    b[k] -= h;
    J_point.col(k) = (eval(pose, a) - eval(pose, b)) / (2 * h);
  }
}

class CostJacobians : public ::testing::Test {
 protected:
  PinholeCamera cam{testing::tum_like_calibration(), 40.0};
  Intrinsics k{cam};
  Eigen::Isometry3d T = testing::camera_pose({0.2, -0.1, 0.3}, {0.1, -0.2, 0.05});
  PoseParams pose = to_pose_params(T);
  Eigen::Vector3d X{0.4, -0.3, 3.5};
  Eigen::Vector2d px{300.0, 250.0};
};

TEST_F(CostJacobians, BaCostsMatchNumericDifferences) {
  const MonoBaCost mono(k, px, 2.0);
  const StereoBaCost stereo(k, px, 290.0, 2.0);
  Eigen::Matrix<double, 2, 7, Eigen::RowMajor> Jm;
  Eigen::Matrix<double, 2, 3, Eigen::RowMajor> Jmp;
  Eigen::Matrix<double, 3, 7, Eigen::RowMajor> Js;
  Eigen::Matrix<double, 3, 3, Eigen::RowMajor> Jsp;
  Eigen::Vector3d r;
  const double* params[2] = {pose.data(), X.data()};
  double* jm[2] = {Jm.data(), Jmp.data()};
  double* js[2] = {Js.data(), Jsp.data()};
  ASSERT_TRUE(mono.Evaluate(params, r.data(), jm));
  ASSERT_TRUE(stereo.Evaluate(params, r.data(), js));
  Eigen::Matrix<double, 2, 6> Nm;
  Eigen::Matrix<double, 2, 3> Nmp;
  Eigen::Matrix<double, 3, 6> Ns;
  Eigen::Matrix<double, 3, 3> Nsp;
  numeric_jacobians<2>(mono, pose, X, Nm, Nmp, true);
  numeric_jacobians<3>(stereo, pose, X, Ns, Nsp, true);
  EXPECT_LT((Jm.leftCols<6>() - Nm).norm(), 1e-4 * Nm.norm());
  EXPECT_LT((Jmp - Nmp).norm(), 1e-4 * Nmp.norm());
  EXPECT_LT((Js.leftCols<6>() - Ns).norm(), 1e-4 * Ns.norm());
  EXPECT_LT((Jsp - Nsp).norm(), 1e-4 * Nsp.norm());
}

TEST_F(CostJacobians, PointBehindCameraFailsEvaluation) {
  const MonoBaCost mono(k, px, 1.0);
  const Eigen::Vector3d behind = T.inverse() * Eigen::Vector3d(0, 0, -1);
  Eigen::Vector2d r;
  const double* params[2] = {pose.data(), behind.data()};
  EXPECT_FALSE(mono.Evaluate(params, r.data(), nullptr));
}

TEST(Se3LeftManifold, PlusMinusRoundTrip) {
  const Se3LeftManifold m;
  const PoseParams x = to_pose_params(testing::camera_pose({1, 2, 3}, {0.3, 0.2, -0.1}));
  const double delta[6] = {0.05, -0.02, 0.1, 0.3, -0.2, 0.1};
  PoseParams y;
  ASSERT_TRUE(m.Plus(x.data(), delta, y.data()));
  double back[6];
  ASSERT_TRUE(m.Minus(y.data(), x.data(), back));
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(back[i], delta[i], 1e-12);
  // Plus is the left update [Exp(omega), v] * T.
  const Eigen::Isometry3d Tx = from_pose_params(x.data()), Ty = from_pose_params(y.data());
  Eigen::Isometry3d D = Eigen::Isometry3d::Identity();
  D.linear() = so3_exp({0.05, -0.02, 0.1});
  D.translation() = Eigen::Vector3d(0.3, -0.2, 0.1);
  EXPECT_LT(((D * Tx).matrix() - Ty.matrix()).norm(), 1e-12);
}

}  // namespace
}  // namespace stillslam
