// Tracker on a synthetic scene: initialization, motion-model and local-map
// tracking, keyframe creation, loss.
#include <gtest/gtest.h>

#include "map/synthetic_scene.h"
#include "stillslam/geometry/se3.h"
#include "stillslam/tracking/tracker.h"

namespace stillslam {
namespace {

TEST(Tracker, TracksSmoothMotionAndCreatesKeyFrames) {
  test::SyntheticScene scene(2500);
  Map map;
  std::vector<KeyFramePtr> inserted;
  LocalMappingLink link;
  std::vector<std::uint64_t> tracked_ids;
  link.insert_keyframe = [&](KeyFramePtr kf, const Frame& tracked) {
    tracked_ids.push_back(tracked.id());
    inserted.push_back(std::move(kf));
  };
  TrackerOptions options;
  options.init_min_keypoints = 300;
  options.init_unmasked_confirm_frames = 0;  // every frame tracked from the first (start check: test_tracker_start_unmasked.cpp)
  Tracker tracker(map, options, link);
  double max_error = 0;
  int keyframes = 0;
  for (int i = 0; i < 40; ++i) {
    const Eigen::Isometry3d T = test::pose_at(0.04 * i, 0.005 * i, 1.0 * i);
    Frame frame = scene.make_frame(static_cast<std::uint64_t>(i), T);
    const TrackingResult r = tracker.track(frame);
    ASSERT_EQ(r.state, TrackingState::Ok) << "frame " << i << ": " << r.reason;
    keyframes += r.new_keyframe ? 1 : 0;
    // The first pose is the world origin: compare relative to frame 0.
    const Eigen::Isometry3d expected = T * test::pose_at(0).inverse();
    const double err = (frame.T_cam_world().inverse().translation() - expected.inverse().translation()).norm();
    max_error = std::max(max_error, err);
    if (i > 0) {
      EXPECT_GT(r.inliers, 100);
    }
  }
  EXPECT_LT(max_error, 1e-4);  // exact measurements
  EXPECT_EQ(static_cast<int>(inserted.size()), keyframes);
  // Each keyframe came with the frame being tracked, here the frame it was made from.
  for (std::size_t k = 0; k < inserted.size(); ++k) EXPECT_EQ(tracked_ids[k], inserted[k]->frame_id()) << k;
  EXPECT_GE(keyframes, 2);
  EXPECT_EQ(map.num_keyframes(), inserted.size());
}

TEST(Tracker, NeedsEnoughDepthToInitialize) {
  test::SyntheticScene scene(200);
  Map map;
  TrackerOptions options;
  options.init_min_keypoints = 500;
  Tracker tracker(map, options, {});
  Frame frame = scene.make_frame(0, test::pose_at(0));
  const TrackingResult r = tracker.track(frame);
  EXPECT_EQ(r.state, TrackingState::NotInitialized);
  EXPECT_NE(r.reason.find("500"), std::string::npos);
  EXPECT_EQ(map.num_keyframes(), 0u);
}

// Segmentation on (frames carry a dynamic mask): the first keyframe waits for
// the next two frames to confirm it.
cv::Mat1b mask_of_left_part(double share) {
  cv::Mat1b mask(480, 640, std::uint8_t{0});
  mask.colRange(0, static_cast<int>(std::lround(share * 640))).setTo(255);
  return mask;
}

TEST(Tracker, WithSegmentationTheNextFramesConfirmTheFirstKeyframe) {
  test::SyntheticScene scene(2500);
  Map map;
  TrackerOptions options;
  options.init_min_keypoints = 300;
  Tracker tracker(map, options, {});
  Frame first = scene.make_frame(0, test::pose_at(0));
  first.set_dynamic_mask(mask_of_left_part(0));
  const TrackingResult waiting = tracker.track(first);
  EXPECT_EQ(waiting.state, TrackingState::NotInitialized);
  EXPECT_NE(waiting.reason.find("next frame"), std::string::npos) << waiting.reason;
  EXPECT_EQ(map.num_keyframes(), 0u);

  Frame second = scene.make_frame(1, test::pose_at(0.01));
  second.set_dynamic_mask(mask_of_left_part(0));
  const TrackingResult confirming = tracker.track(second);
  EXPECT_EQ(confirming.state, TrackingState::NotInitialized);
  EXPECT_NE(confirming.reason.find("1 of 2"), std::string::npos) << confirming.reason;

  Frame third = scene.make_frame(2, test::pose_at(0.02));
  third.set_dynamic_mask(mask_of_left_part(0));
  const TrackingResult r = tracker.track(third);
  ASSERT_EQ(r.state, TrackingState::Ok) << r.reason;
  ASSERT_EQ(map.num_keyframes(), 1u);
  EXPECT_EQ(map.keyframes().front()->frame_id(), 0u);  // the map starts at the first frame
  EXPECT_LT((third.T_cam_world().inverse().translation() - Eigen::Vector3d(0.02, 0, 0)).norm(), 1e-4);
}

TEST(Tracker, WaitsForTwoFramesThatAreNotMostlyMasked) {
  test::SyntheticScene scene(2500);
  Map map;
  TrackerOptions options;
  options.init_min_keypoints = 300;
  options.init_wait_frames = 3;
  Tracker tracker(map, options, {});
  std::uint64_t id = 0;
  // Too little depth: waiting for that does not use up the wait.
  for (int i = 0; i < 5; ++i) {
    test::SyntheticScene sparse(100);
    Frame f = sparse.make_frame(id++, test::pose_at(0));
    f.set_dynamic_mask(mask_of_left_part(0.7));
    EXPECT_EQ(tracker.track(f).state, TrackingState::NotInitialized);
  }
  // The first frame with depth becomes the candidate, the next three reject it.
  for (int i = 0; i < 4; ++i) {
    Frame f = scene.make_frame(id++, test::pose_at(0));
    f.set_dynamic_mask(mask_of_left_part(0.7));
    const TrackingResult r = tracker.track(f);
    EXPECT_EQ(r.state, TrackingState::NotInitialized) << "frame " << i;
    if (i > 0) {
      EXPECT_NE(r.reason.find("70 %"), std::string::npos) << r.reason;
    }
  }
  EXPECT_EQ(map.num_keyframes(), 0u);
  // After the wait, a mostly masked view starts the map anyway.
  Frame f = scene.make_frame(id++, test::pose_at(0));
  f.set_dynamic_mask(mask_of_left_part(0.7));
  EXPECT_EQ(tracker.track(f).state, TrackingState::Ok);
  EXPECT_EQ(map.num_keyframes(), 1u);
}

TEST(Tracker, LostWhenTheViewJumpsAwayAndRecoversWhenBack) {
  test::SyntheticScene scene(2500);
  Map map;
  TrackerOptions options;
  options.init_min_keypoints = 300;
  options.init_unmasked_confirm_frames = 0;  // every frame tracked from the first (start check: test_tracker_start_unmasked.cpp)
  Tracker tracker(map, options, {});
  for (int i = 0; i < 5; ++i) {
    Frame f = scene.make_frame(static_cast<std::uint64_t>(i), test::pose_at(0.01 * i));
    ASSERT_EQ(tracker.track(f).state, TrackingState::Ok);
  }
  // Looking backwards: no scene point in view.
  Frame away = scene.make_frame(5, test::pose_at(0.05, 0, 180));
  const TrackingResult lost = tracker.track(away);
  EXPECT_EQ(lost.state, TrackingState::Lost);
  EXPECT_FALSE(lost.reason.empty());
  // Back near the last good pose: the wide-window search finds the map again.
  Frame back = scene.make_frame(6, test::pose_at(0.045));
  const TrackingResult r = tracker.track(back);
  EXPECT_EQ(r.state, TrackingState::Ok) << r.reason;
  EXPECT_LT((back.T_cam_world().inverse().translation() - Eigen::Vector3d(0.045, 0, 0)).norm(), 1e-4);
}

}  // namespace
}  // namespace stillslam
