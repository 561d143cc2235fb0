// Trajectory refinement: a frame tracked against a map that was later
// corrected is re-registered against the corrected points.
#include <gtest/gtest.h>

#include <cstdio>

#include "../map/synthetic_scene.h"
#include "stillslam/map/map.h"
#include "stillslam/system/trajectory_refinement.h"

namespace stillslam {
namespace {

// A frame at cam_from_world whose every keypoint is matched to a map point
// observed by one keyframe (the frame itself) at its true position.
struct TrackedFrame {
  Map map;
  Frame frame;
  KeyFramePtr keyframe;
  std::vector<MapPointPtr> points;
};

std::unique_ptr<TrackedFrame> tracked_frame(const test::SyntheticScene& scene, const Eigen::Isometry3d& cam_from_world) {
  auto t = std::make_unique<TrackedFrame>();
  std::vector<std::size_t> point_of_keypoint;
  t->frame = scene.make_frame(1, cam_from_world, &point_of_keypoint);
  t->frame.set_pose(cam_from_world);
  t->keyframe = t->map.create_keyframe(t->frame);
  for (std::size_t i = 0; i < t->frame.size(); ++i) {
    MapPointPtr mp = t->map.create_map_point(scene.points()[point_of_keypoint[i]], t->keyframe.get());
    mp->add_observation(t->keyframe.get(), i);
    t->frame.set_map_point(i, mp);
    t->points.push_back(std::move(mp));
  }
  return t;
}

double translation_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.inverse().translation() - b.inverse().translation()).norm();
}

// The map drifted by `shift` (metres along x) while the frame was tracked:
// its tracked pose is off by the same amount.
Eigen::Isometry3d shifted(const Eigen::Isometry3d& cam_from_world, double shift) {
  return cam_from_world * Eigen::Translation3d(-shift, 0, 0);
}

TEST(TrajectoryRefinement, RegistersTheFrameAgainstTheCorrectedMap) {
  const test::SyntheticScene scene(1500);
  const Eigen::Isometry3d truth = test::pose_at(0.1, 0.02, 5);
  auto t = tracked_frame(scene, truth);
  const FrameObservations obs = collect_frame_observations(t->frame);
  ASSERT_EQ(obs.points.size(), t->frame.size());
  const Eigen::Isometry3d tracked = shifted(truth, 0.01);
  ASSERT_NEAR(translation_error(tracked, truth), 0.01, 1e-9);

  const auto refined = refine_frame_pose(*scene.setup(), tracked, obs, {});
  ASSERT_TRUE(refined.has_value());
  EXPECT_LT(translation_error(*refined, truth), 1e-6);
}

TEST(TrajectoryRefinement, FusedPointsCountAsTheirReplacement) {
  const test::SyntheticScene scene(1500);
  const Eigen::Isometry3d truth = test::pose_at(-0.05, 0, -3);
  auto t = tracked_frame(scene, truth);
  const FrameObservations obs = collect_frame_observations(t->frame);
  // Every observed point was fused into a duplicate (in a chain of two for
  // every other one) that holds the true position; the originals are left
  // 5 cm off, all in the same direction, so using them would bias the pose.
  for (std::size_t k = 0; k < t->points.size(); ++k) {
    const MapPointPtr& original = t->points[k];
    const Eigen::Vector3d true_position = original->position();
    MapPointPtr duplicate = t->map.create_map_point(true_position + Eigen::Vector3d(0, 0.05, 0), nullptr);
    original->replace_with(duplicate);
    original->set_position(true_position + Eigen::Vector3d(0.05, 0, 0));
    if (k % 2 == 0) {
      MapPointPtr second = t->map.create_map_point(true_position, nullptr);
      duplicate->replace_with(second);
    } else {
      duplicate->set_position(true_position);
    }
  }
  const auto refined = refine_frame_pose(*scene.setup(), shifted(truth, 0.01), obs, {});
  ASSERT_TRUE(refined.has_value());
  EXPECT_LT(translation_error(*refined, truth), 1e-6);
}

TEST(TrajectoryRefinement, KeepsTheTrackedPoseWhenTooFewPointsSurvive) {
  const test::SyntheticScene scene(1500);
  const Eigen::Isometry3d truth = test::pose_at(0.02);
  auto t = tracked_frame(scene, truth);
  const FrameObservations obs = collect_frame_observations(t->frame);
  TrajectoryRefinementOptions options;
  options.min_inliers = 30;
  ASSERT_GT(t->points.size(), 100u);
  for (std::size_t k = 29; k < t->points.size(); ++k) t->points[k]->set_bad();  // culled
  EXPECT_FALSE(refine_frame_pose(*scene.setup(), shifted(truth, 0.01), obs, options).has_value());

  options.min_inliers = 20;
  const auto refined = refine_frame_pose(*scene.setup(), shifted(truth, 0.01), obs, options);
  ASSERT_TRUE(refined.has_value());
  EXPECT_LT(translation_error(*refined, truth), 1e-6);
}

// A third of the points lie on a person kept as static (issue #19) who swayed
// 5 mm after they were made: with leave_out_kept_points they leave the
// re-estimate while enough others remain, and are used when too few do.
TEST(TrajectoryRefinement, LeavesOutPointsOnAKeptPersonWhileEnoughOthersRemain) {
  const test::SyntheticScene scene(1500);
  const Eigen::Isometry3d truth = test::pose_at(0.05, 0.01, 4);
  auto t = tracked_frame(scene, truth);
  const FrameObservations obs = collect_frame_observations(t->frame);
  ASSERT_GT(t->points.size(), 150u);
  for (std::size_t k = 0; k < t->points.size(); k += 3) {
    t->points[k]->mark_on_dynamic_instance();
    t->points[k]->set_position(t->points[k]->position() + Eigen::Vector3d(0.005, 0, 0));
  }
  TrajectoryRefinementOptions options;
  const auto with_person = refine_frame_pose(*scene.setup(), shifted(truth, 0.01), obs, options);
  options.leave_out_kept_points = true;
  const auto without = refine_frame_pose(*scene.setup(), shifted(truth, 0.01), obs, options);
  ASSERT_TRUE(with_person.has_value());
  ASSERT_TRUE(without.has_value());
  std::printf("error with the kept person's points %.5f m, without %.7f m\n", translation_error(*with_person, truth),
              translation_error(*without, truth));
  EXPECT_GT(translation_error(*with_person, truth), 5e-4);
  EXPECT_LT(translation_error(*without, truth), 1e-6);
  // Kept with 5x their sigma: a fraction of their pull.
  options.leave_out_kept_points = false;
  options.kept_point_sigma = 5;
  const auto weighted = refine_frame_pose(*scene.setup(), shifted(truth, 0.01), obs, options);
  ASSERT_TRUE(weighted.has_value());
  std::printf("error with them at 5x sigma %.6f m\n", translation_error(*weighted, truth));
  EXPECT_LT(translation_error(*weighted, truth), translation_error(*with_person, truth) / 3);
  EXPECT_GT(translation_error(*weighted, truth), translation_error(*without, truth));
  options.kept_point_sigma = 1;

  // Only 20 points off the person survive (fewer than min_inliers 30): all points, as without the rule.
  int others = 0;
  for (std::size_t k = 0; k < t->points.size(); ++k) {
    if (k % 3 != 0 && ++others > 20) t->points[k]->set_bad();
  }
  options.leave_out_kept_points = false;
  const auto all_off = refine_frame_pose(*scene.setup(), shifted(truth, 0.01), obs, options);
  options.leave_out_kept_points = true;
  const auto all_on = refine_frame_pose(*scene.setup(), shifted(truth, 0.01), obs, options);
  ASSERT_TRUE(all_off.has_value());
  ASSERT_TRUE(all_on.has_value());
  EXPECT_GT(translation_error(*all_on, truth), 5e-4);
  EXPECT_LT((all_on->translation() - all_off->translation()).norm(), 1e-9);
}

TEST(TrajectoryRefinement, KeepsOnlyInlierMatchesOfRealMapPoints) {
  const test::SyntheticScene scene(1500);
  auto t = tracked_frame(scene, test::pose_at(0));
  const std::size_t n = t->frame.size();
  ASSERT_GT(n, 100u);
  t->frame.set_outlier(0, true);
  t->frame.set_outlier(1, true);
  // The tracker's temporary odometry points have no keyframe observation.
  t->frame.set_map_point(2, std::make_shared<MapPoint>(999999, Eigen::Vector3d(0, 0, 3), nullptr));
  t->frame.set_map_point(3, nullptr);
  const FrameObservations obs = collect_frame_observations(t->frame);
  EXPECT_EQ(obs.points.size(), n - 4);
  ASSERT_EQ(obs.observations.size(), obs.points.size());
  EXPECT_EQ(obs.points.front(), t->points[4]);
  EXPECT_FLOAT_EQ(obs.observations.front().x, t->frame.keypoint(4).pt.x);
  EXPECT_FLOAT_EQ(obs.observations.front().u_right, t->frame.u_right(4));
}

}  // namespace
}  // namespace stillslam
