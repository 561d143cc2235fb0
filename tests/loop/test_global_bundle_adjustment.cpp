// Global BA steps: abort leaves the map untouched; keyframes and points
// created after the snapshot follow their parent's / reference's correction.
#include <gtest/gtest.h>

#include <atomic>

#include "loop/loop_scene.h"
#include "stillslam/geometry/se3.h"
#include "stillslam/loop/global_bundle_adjustment.h"

namespace stillslam {
namespace {

TEST(GlobalBundleAdjustment, AbortedSolveChangesNothing) {
  test::LoopScene scene;
  for (int i = 0; i < 8; ++i) scene.add_keyframe(i);
  const GlobalBundleAdjustmentProblem problem = snapshot_global_problem(scene.map());
  ASSERT_EQ(problem.keyframes.size(), 8u);
  EXPECT_TRUE(problem.ba_keyframes[0].fixed);
  EXPECT_FALSE(problem.ba_keyframes[1].fixed);
  std::atomic<bool> abort{true};
  BundleAdjustmentOptions options;
  options.abort = &abort;
  const BundleAdjustmentResult result = solve_global_problem(problem, options);
  EXPECT_TRUE(result.aborted);
  const Eigen::Isometry3d before = scene.map().keyframe(5)->T_cam_world();
  EXPECT_EQ(apply_global_result(scene.map(), problem, result), 0);
  EXPECT_TRUE(scene.map().keyframe(5)->T_cam_world().isApprox(before, 0.0));
}

TEST(GlobalBundleAdjustment, LateKeyframesFollowTheirParent) {
  // The drifted map is inconsistent (odometry bias), so BA moves keyframes.
  test::LoopScene scene;
  for (int i = 0; i < 12; ++i) scene.add_keyframe(i);
  const GlobalBundleAdjustmentProblem problem = snapshot_global_problem(scene.map());
  const BundleAdjustmentResult result = solve_global_problem(problem, {});
  ASSERT_FALSE(result.aborted);
  // Created while BA ran: its pose relative to its parent must be kept.
  const KeyFramePtr late = scene.add_keyframe(12);
  ASSERT_NE(late->parent(), nullptr);
  const Eigen::Isometry3d T_parent_late = late->parent()->T_cam_world() * late->T_world_cam();
  MapPointPtr late_point;
  for (const MapPointPtr& mp : late->map_points()) {
    if (mp && mp->first_keyframe_id() == 12u) late_point = mp;
  }
  ASSERT_NE(late_point, nullptr);
  const Eigen::Vector3d point_in_late = late->T_cam_world() * late_point->position();
  const Eigen::Isometry3d parent_before = late->parent()->T_cam_world();

  EXPECT_EQ(apply_global_result(scene.map(), problem, result), 1);
  const KeyFrame* parent = late->parent();
  EXPECT_GT((parent->T_cam_world().translation() - parent_before.translation()).norm(), 1e-4);
  const Eigen::Isometry3d T_parent_late_after = parent->T_cam_world() * late->T_world_cam();
  EXPECT_LT((T_parent_late_after.translation() - T_parent_late.translation()).norm(), 1e-9);
  EXPECT_LT(rotation_angle(T_parent_late_after.inverse() * T_parent_late), 1e-9);
  EXPECT_LT((late->T_cam_world() * late_point->position() - point_in_late).norm(), 1e-9);
}

}  // namespace
}  // namespace stillslam
