// The keyframe rate tracking hands to an idle mapper (issue #21): with the
// default TrackerOptions the keyframe budget bounds it; without the budget an
// always-idle mapper gets far more keyframes on the same frames; frames with
// fewer inliers than keyframe_budget_inliers take theirs outside the budget.
#include <gtest/gtest.h>

#include "map/synthetic_scene.h"
#include "stillslam/tracking/tracker.h"

namespace stillslam {
namespace {

struct RateRun {
  int keyframes = 0;
  double seconds = 0;  // input time from the first keyframe to the last frame
};

// A camera panning over the scene, 10 frames per second (synthetic_scene.h
// stamps frame i at 0.1 i s); the "mapper" only adds each keyframe as an
// observation of the points tracking matched in it (as local mapping's
// registration does) and is always idle.
RateRun keyframes_made(TrackerOptions options, int frames) {
  options.init_min_keypoints = 300;
  options.init_unmasked_confirm_frames = 0;  // every frame tracked from the first (start check: test_tracker_start_unmasked.cpp)
  // Every frame wants a keyframe (the RGB-D rule "too few close points
  // tracked", as on the RGB-D renders), so only the budget limits them.
  options.close_points_tracked_min = 50000;
  options.close_points_untracked_min = 0;
  test::SyntheticScene scene(3000);
  Map map;
  LocalMappingLink link;
  link.insert_keyframe = [](KeyFramePtr kf, const Frame&) {
    const std::vector<MapPointPtr>& points = kf->map_points();
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (points[i] && !points[i]->is_observed_by(kf.get())) points[i]->add_observation(kf.get(), i);
    }
    kf->update_connections();
  };
  Tracker tracker(map, options, link);
  RateRun run;
  double first = -1, last = 0;
  for (int i = 0; i < frames; ++i) {
    Frame frame = scene.make_frame(static_cast<std::uint64_t>(i), test::pose_at(0.03 * i, 0, 1.5 * i - 30));
    const TrackingResult r = tracker.track(frame);
    EXPECT_EQ(r.state, TrackingState::Ok) << "frame " << i << ": " << r.reason;
    if (r.new_keyframe) {
      ++run.keyframes;
      if (first < 0) first = frame.timestamp();
    }
    last = frame.timestamp();
  }
  run.seconds = last - first;
  return run;
}

TEST(TrackerKeyframeRate, TheDefaultBudgetBoundsTheRateOfAnIdleMapper) {
  TrackerOptions options;
  const KeyFrameBudgetOptions budget = options.keyframe_budget;
  ASSERT_GT(budget.per_second, 0) << "the budget is on by default";
  ASSERT_GT(budget.start_keyframes, 1) << "a map's first keyframes are outside it by default";
  const RateRun bounded = keyframes_made(options, 40);

  options.keyframe_budget.start_keyframes = 0;
  const RateRun no_start = keyframes_made(options, 40);

  options.keyframe_budget.per_second = 0;
  const RateRun unbounded = keyframes_made(options, 40);

  // Without the start exemption: the first keyframe (the map's start) plus
  // the burst plus the rate.
  const double cap = 1 + budget.burst + budget.per_second * no_start.seconds;
  EXPECT_LE(no_start.keyframes, cap);
  EXPECT_GE(no_start.keyframes, cap - 2);  // the budget, not tracking, limits it here
  // With it (the default) the map's first keyframes come on top, less what
  // the bucket did not gather meanwhile; never more than all of them on top.
  EXPECT_GT(bounded.keyframes, no_start.keyframes + 2);
  EXPECT_LE(bounded.keyframes, no_start.keyframes + budget.start_keyframes - 1);
  EXPECT_GT(unbounded.keyframes, bounded.keyframes + 5);
}

TEST(TrackerKeyframeRate, FramesWithFewInliersTakeKeyframesOutsideTheBudget) {
  TrackerOptions options;
  options.keyframe_budget.per_second = 0;
  const RateRun unbounded = keyframes_made(options, 40);

  // A budget that is empty after the first keyframe.
  options.keyframe_budget = {0.001, 1, 0};
  options.keyframe_budget_inliers = 0;  // only tracking about to fail is exempt
  const RateRun empty = keyframes_made(options, 40);
  EXPECT_LE(empty.keyframes, 3);

  options.keyframe_budget_inliers = 50000;  // every frame is exempt
  const RateRun exempt = keyframes_made(options, 40);
  EXPECT_EQ(exempt.keyframes, unbounded.keyframes);
}

}  // namespace
}  // namespace stillslam
