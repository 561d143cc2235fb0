// optimize entry points reject inconsistent input with a PreconditionError.
#include <gtest/gtest.h>

#include <limits>

#include "common/precondition.h"
#include "geometry/synthetic_scene.h"
#include "stillslam/optimize/bundle_adjustment.h"
#include "stillslam/optimize/pose_graph.h"
#include "stillslam/optimize/pose_optimizer.h"

namespace stillslam {
namespace {

TEST(OptimizePreconditions, PoseGraphEdgesStayInsideTheNodes) {
  const std::vector<Eigen::Isometry3d> nodes(2, Eigen::Isometry3d::Identity());
  PoseGraphEdge edge;
  edge.from = 0;
  edge.to = 5;
  test::expect_precondition([&] { optimize_pose_graph(nodes, {edge}, {0}); }, "src/stillslam/optimize/pose_graph.cpp",
                            "optimize_pose_graph: an edge ends outside the nodes (check failed: e.to < n, 5 vs 2)");
}

TEST(OptimizePreconditions, BundleAdjustmentObservationsIndexGivenPoints) {
  const PinholeCamera cam(testing::tum_like_calibration());
  BaObservation observation;
  observation.keyframe = 0;
  observation.point = 3;
  test::expect_precondition([&] { bundle_adjust(cam, {BaKeyframe{}}, {BaPoint{}}, {observation}); },
                            "src/stillslam/optimize/bundle_adjustment.cpp",
                            "bundle_adjust: observation 0 refers to a point it was not given (check failed: "
                            "observations[i].point < points.size(), 3 vs 1)");
}

TEST(OptimizePreconditions, PoseOptimizationStartsFromAFinitePose) {
  const PinholeCamera cam(testing::tum_like_calibration());
  Eigen::Isometry3d nan_pose = Eigen::Isometry3d::Identity();
  nan_pose.translation().x() = std::numeric_limits<double>::quiet_NaN();
  test::expect_precondition([&] { optimize_pose(cam, nan_pose, {PoseObservation{}}); },
                            "src/stillslam/optimize/pose_optimizer.cpp",
                            "optimize_pose: the initial pose is not finite (check failed: "
                            "T_cam_world_init.matrix().allFinite())");
}

}  // namespace
}  // namespace stillslam
