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
  link.insert_keyframe = [&](KeyFramePtr kf) { inserted.push_back(std::move(kf)); };
  TrackerOptions options;
  options.init_min_keypoints = 300;
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

TEST(Tracker, WaitsForAViewThatIsNotMostlyMasked) {
  test::SyntheticScene scene(2500);
  Map map;
  TrackerOptions options;
  options.init_min_keypoints = 300;
  options.init_max_masked_fraction = 0.5;
  options.init_masked_wait_frames = 3;
  Tracker tracker(map, options, {});
  std::uint64_t id = 0;
  // Too little depth: waiting for that does not use up the masked-view wait.
  for (int i = 0; i < 5; ++i) {
    test::SyntheticScene sparse(100);
    Frame f = sparse.make_frame(id++, test::pose_at(0));
    f.set_masked_fraction(0.7f);
    EXPECT_EQ(tracker.track(f).state, TrackingState::NotInitialized);
  }
  for (int i = 0; i < 3; ++i) {
    Frame f = scene.make_frame(id++, test::pose_at(0));
    f.set_masked_fraction(0.7f);
    const TrackingResult r = tracker.track(f);
    EXPECT_EQ(r.state, TrackingState::NotInitialized) << "frame " << i;
    EXPECT_NE(r.reason.find("70 %"), std::string::npos) << r.reason;
  }
  EXPECT_EQ(map.num_keyframes(), 0u);
  // After the wait, a mostly masked view starts the map anyway.
  Frame f = scene.make_frame(id++, test::pose_at(0));
  f.set_masked_fraction(0.7f);
  EXPECT_EQ(tracker.track(f).state, TrackingState::Ok);
  EXPECT_EQ(map.num_keyframes(), 1u);

  // A view half masked or less starts at once.
  Map other;
  Tracker fresh(other, options, {});
  Frame g = scene.make_frame(0, test::pose_at(0));
  g.set_masked_fraction(0.5f);
  EXPECT_EQ(fresh.track(g).state, TrackingState::Ok);
}

TEST(Tracker, LostWhenTheViewJumpsAwayAndRecoversWhenBack) {
  test::SyntheticScene scene(2500);
  Map map;
  TrackerOptions options;
  options.init_min_keypoints = 300;
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
