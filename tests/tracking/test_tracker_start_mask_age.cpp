// The map's first keyframe obeys the keyframe mask-age rule
// (TrackerOptions::max_keyframe_mask_age, Segmentation.keyframeMaskAge in
// async mode): a frame whose carried mask is too old does not start the map;
// it asks for a segmentation slot and the next young-mask frame starts it.
#include <gtest/gtest.h>

#include "map/synthetic_scene.h"
#include "stillslam/tracking/tracker.h"

namespace stillslam {
namespace {

Frame masked_frame(const test::SyntheticScene& scene, std::uint64_t id, double x, int mask_age) {
  Frame f = scene.make_frame(id, test::pose_at(x));
  cv::Mat1b mask = cv::Mat1b::zeros(480, 640);
  mask(cv::Rect(0, 0, 40, 40)).setTo(255);  // someone in a corner
  f.set_dynamic_mask(mask);
  f.set_mask_age(mask_age);
  return f;
}

TEST(TrackerStartMaskAge, AStaleMaskDoesNotStartTheMap) {
  test::SyntheticScene scene(2500);
  Map map;
  TrackerOptions options;
  options.init_min_keypoints = 300;
  options.max_keyframe_mask_age = 2;
  Tracker tracker(map, options, {});

  Frame stale = masked_frame(scene, 0, 0, 5);
  const TrackingResult waiting = tracker.track(stale);
  EXPECT_EQ(waiting.state, TrackingState::NotInitialized);
  EXPECT_TRUE(waiting.keyframe_deferred);
  EXPECT_NE(waiting.reason.find("fresher mask"), std::string::npos) << waiting.reason;

  Frame young = masked_frame(scene, 1, 0.01, 0);
  const TrackingResult candidate = tracker.track(young);
  EXPECT_EQ(candidate.state, TrackingState::NotInitialized);
  EXPECT_FALSE(candidate.keyframe_deferred);
  EXPECT_NE(candidate.reason.find("next frame"), std::string::npos) << candidate.reason;

  // Confirming frames only check the view: their age does not matter.
  Frame second = masked_frame(scene, 2, 0.02, 1), third = masked_frame(scene, 3, 0.03, 2);
  tracker.track(second);
  const TrackingResult r = tracker.track(third);
  ASSERT_EQ(r.state, TrackingState::Ok) << r.reason;
  ASSERT_EQ(map.num_keyframes(), 1u);
  EXPECT_EQ(map.keyframes().front()->frame_id(), 1u);  // the young-mask frame, not frame 0
}

TEST(TrackerStartMaskAge, AnyAgeStartsTheMapWhenTheRuleIsOff) {
  test::SyntheticScene scene(2500);
  Map map;
  TrackerOptions options;
  options.init_min_keypoints = 300;
  Tracker tracker(map, options, {});
  for (std::uint64_t i = 0; i < 3; ++i) {
    Frame f = masked_frame(scene, i, 0.01 * static_cast<double>(i), 9);
    tracker.track(f);
  }
  ASSERT_EQ(map.num_keyframes(), 1u);
  EXPECT_EQ(map.keyframes().front()->frame_id(), 0u);
}

}  // namespace
}  // namespace stillslam
