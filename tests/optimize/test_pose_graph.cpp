#include <gtest/gtest.h>

#include "geometry/synthetic_scene.h"
#include "stillslam/core/error.h"
#include "stillslam/optimize/pose_graph.h"

namespace stillslam {
namespace {

// 60 poses on a 4 m radius circle; odometry edges carry a 0.4 deg/step yaw
// bias plus noise, so integrating them drifts by metres; one loop edge from
// the last pose to the first (true relative pose) closes the circle.
TEST(PoseGraph, LoopEdgeRemovesDrift) {
  const int n = 60;
  std::vector<Eigen::Isometry3d> truth;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = so3_exp({0, a, 0});
    T.translation() = Eigen::Vector3d(4 * std::sin(a), 0.2 * std::sin(3 * a), 4 * std::cos(a));
    truth.push_back(T);
  }
  std::mt19937 rng(41);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<PoseGraphEdge> edges;
  for (int i = 0; i + 1 < n; ++i) {
    Eigen::Isometry3d rel = truth[i].inverse() * truth[i + 1];
    Vector6d xi;
    xi << 0.002 * noise(rng), 0.4 * M_PI / 180 + 0.002 * noise(rng), 0.002 * noise(rng), 0.01 * noise(rng),
        0.01 * noise(rng), 0.01 * noise(rng);
    rel = rel * se3_exp(xi);
    edges.push_back({static_cast<std::size_t>(i), static_cast<std::size_t>(i + 1), rel, 1.0});
  }
  // Initial guess: dead reckoning along the drifting odometry.
  std::vector<Eigen::Isometry3d> init = {truth[0]};
  for (const auto& e : edges) init.push_back(init.back() * e.T_from_to);
  auto max_error = [&](const std::vector<Eigen::Isometry3d>& est) {
    double m = 0;
    for (int i = 0; i < n; ++i) m = std::max(m, (est[i].translation() - truth[i].translation()).norm());
    return m;
  };
  const double drift = max_error(init);
  ASSERT_GT(drift, 1.0);

  // Without the loop edge nothing changes (odometry is self-consistent).
  const auto no_loop = optimize_pose_graph(init, edges, {0});
  EXPECT_NEAR(max_error(no_loop), drift, 1e-6);

  edges.push_back({static_cast<std::size_t>(n - 1), 0, truth[n - 1].inverse() * truth[0], 10.0});
  const auto corrected = optimize_pose_graph(init, edges, {0});
  const double after = max_error(corrected);
  EXPECT_LT(after, drift / 10.0);
  EXPECT_EQ(corrected[0].matrix(), init[0].matrix());  // fixed node unchanged
  // The loop edge is satisfied closely.
  const Eigen::Isometry3d loop = corrected[n - 1].inverse() * corrected[0];
  EXPECT_LT((loop.translation() - (truth[n - 1].inverse() * truth[0]).translation()).norm(), 0.05);
}

TEST(PoseGraph, RejectsBadIndices) {
  std::vector<Eigen::Isometry3d> nodes(2, Eigen::Isometry3d::Identity());
  EXPECT_THROW(optimize_pose_graph(nodes, {{0, 2, Eigen::Isometry3d::Identity(), 1.0}}, {}), Error);
  EXPECT_THROW(optimize_pose_graph(nodes, {{0, 1, Eigen::Isometry3d::Identity(), 1.0}}, {5}), Error);
}

}  // namespace
}  // namespace stillslam
