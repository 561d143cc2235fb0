// A map start whose confirming frame is far from the first (--realtime drops
// 75-85 % of the frames while the segmenter is slow): the tracker starts the
// confirming frame at the initial view check's PnP motion, not at the first
// frame's pose, so it is tracked and the map starts.
#include <gtest/gtest.h>

#include "map/synthetic_scene.h"
#include "stillslam/tracking/tracker.h"

namespace stillslam {
namespace {

Frame masked_frame(const test::SyntheticScene& scene, std::uint64_t id, const Eigen::Isometry3d& T_cam_world) {
  Frame f = scene.make_frame(id, T_cam_world);
  cv::Mat1b mask = cv::Mat1b::zeros(480, 640);
  mask(cv::Rect(0, 0, 40, 40)).setTo(255);  // someone in a corner: the start is checked
  f.set_dynamic_mask(mask);
  return f;
}

TEST(TrackerStartFar, TheConfirmingFrameStartsAtThePnpMotion) {
  test::SyntheticScene scene(2500);
  Map map;
  TrackerOptions options;
  options.init_min_keypoints = 300;
  Tracker tracker(map, options, {});
  // Frames 0, 1 and 2 of the run, seen 6 input frames apart: 0.2 m and 8
  // degrees of yaw between neighbours, about 90 px of image motion.
  const Eigen::Isometry3d poses[] = {test::pose_at(0), test::pose_at(0.2, 0, 8), test::pose_at(0.4, 0.05, 16)};
  Frame first = masked_frame(scene, 0, poses[0]);
  EXPECT_EQ(tracker.track(first).state, TrackingState::NotInitialized);
  Frame second = masked_frame(scene, 6, poses[1]);
  const TrackingResult confirming = tracker.track(second);
  EXPECT_EQ(confirming.state, TrackingState::NotInitialized) << confirming.reason;
  Frame third = masked_frame(scene, 12, poses[2]);
  const TrackingResult r = tracker.track(third);
  ASSERT_EQ(r.state, TrackingState::Ok) << r.reason;
  ASSERT_EQ(map.num_keyframes(), 1u);
  EXPECT_EQ(map.keyframes().front()->frame_id(), 0u);
  // The map's frame is the first camera's: the third frame's pose is its motion from there.
  const Eigen::Isometry3d truth = poses[2] * poses[0].inverse();
  EXPECT_LT((third.T_cam_world().translation() - truth.translation()).norm(), 0.01);
  EXPECT_LT(Eigen::AngleAxisd(third.T_cam_world().linear().transpose() * truth.linear()).angle(), 0.01);
  EXPECT_GT(r.inliers, 300);
}

}  // namespace
}  // namespace stillslam
