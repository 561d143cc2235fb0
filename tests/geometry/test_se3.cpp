#include <gtest/gtest.h>

#include <random>

#include "stillslam/geometry/se3.h"

namespace stillslam {
namespace {

TEST(Se3, So3ExpLogRoundTrip) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    Eigen::Vector3d w(u(rng), u(rng), u(rng));
    w *= (i % 4 == 0 ? 1e-9 : 3.0);  // tiny and large angles
    if (w.norm() > 3.1) w *= 3.1 / w.norm();
    const Eigen::Matrix3d R = so3_exp(w);
    EXPECT_LT((R * R.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_LT((so3_log(R) - w).norm(), 1e-9) << w.transpose();
    EXPECT_NEAR(rotation_angle(R), w.norm(), 1e-9);
  }
  // Exactly pi: the log has norm pi and reproduces R.
  const Eigen::Matrix3d Rpi = so3_exp(Eigen::Vector3d(0, 3.14159265358979323846, 0));
  EXPECT_NEAR(so3_log(Rpi).norm(), 3.14159265358979323846, 1e-9);
  EXPECT_LT((so3_exp(so3_log(Rpi)) - Rpi).norm(), 1e-9);
}

TEST(Se3, Se3ExpLogRoundTripAndFirstOrder) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    Vector6d xi;
    for (int k = 0; k < 6; ++k) xi[k] = 2.0 * u(rng);
    if (xi.head<3>().norm() > 3.0) xi.head<3>() *= 3.0 / xi.head<3>().norm();
    const Eigen::Isometry3d T = se3_exp(xi);
    EXPECT_LT((se3_log(T) - xi).norm(), 1e-9);
  }
  // Pure translation: v is the translation.
  Vector6d xi = Vector6d::Zero();
  xi.tail<3>() << 1, 2, 3;
  EXPECT_LT((se3_exp(xi).translation() - Eigen::Vector3d(1, 2, 3)).norm(), 1e-15);
  // Known closed form: rotate pi/2 about z with v = (1, 0, 0):
  // t = J v, J = I + (1 - cos)/th^2 W + (th - sin)/th^3 W^2.
  xi << 0, 0, M_PI / 2, 1, 0, 0;
  const Eigen::Vector3d t = se3_exp(xi).translation();
  EXPECT_NEAR(t.x(), 2.0 / M_PI, 1e-12);
  EXPECT_NEAR(t.y(), 2.0 / M_PI, 1e-12);
  EXPECT_NEAR(t.z(), 0.0, 1e-12);
}

TEST(Se3, InterpolateEndpointsAndMidpoint) {
  const Eigen::Isometry3d a = se3_exp((Vector6d() << 0.1, 0.2, 0.3, 1, 2, 3).finished());
  const Eigen::Isometry3d b = se3_exp((Vector6d() << 0.1, 0.2, 1.3, -1, 0, 5).finished());
  EXPECT_LT((interpolate(a, b, 0).matrix() - a.matrix()).norm(), 1e-12);
  EXPECT_LT((interpolate(a, b, 1).matrix() - b.matrix()).norm(), 1e-12);
  const Eigen::Isometry3d m = interpolate(a, b, 0.5);
  EXPECT_NEAR(rotation_angle(a.linear().transpose() * m.linear()),
              0.5 * rotation_angle(a.linear().transpose() * b.linear()), 1e-12);
  EXPECT_LT((m.translation() - 0.5 * (a.translation() + b.translation())).norm(), 1e-12);
}

TEST(Se3, Sim3ComposeInverseAct) {
  const Sim3 A(2.0, so3_exp({0.1, -0.4, 0.3}), {1, 2, 3});
  const Sim3 B(0.5, so3_exp({-0.7, 0.2, 0.1}), {-1, 0, 4});
  const Eigen::Vector3d x(0.3, -2, 5);
  EXPECT_LT(((A * B) * x - A * (B * x)).norm(), 1e-12);
  EXPECT_LT((A.inverse() * (A * x) - x).norm(), 1e-12);
  EXPECT_LT(((A * A.inverse()).matrix() - Eigen::Matrix4d::Identity()).norm(), 1e-12);
  EXPECT_LT((A.matrix() * x.homogeneous() - (A * x).homogeneous()).norm(), 1e-12);
  EXPECT_DOUBLE_EQ((A * B).s, 1.0);
  const Eigen::Isometry3d T = se3_exp((Vector6d() << 0.1, 0.2, 0.3, 1, 2, 3).finished());
  EXPECT_LT((Sim3(T) * x - T * x).norm(), 1e-12);
  EXPECT_LT((Sim3(T).rigid().matrix() - T.matrix()).norm(), 1e-15);
}

}  // namespace
}  // namespace stillslam
