// A map start without segmentation in a view a third of which walks: the
// first keyframe waits for the next frames' geometric check and takes none of
// the walkers' points; the velocity after the start is per frame; in the
// frames after the start the keyframes take no walkers' points either
// (tracking/start_evidence.h). Where the check finds less than
// initUnmaskedMovingShare of the view moving, the first keyframe is kept
// whole, as a start without the check keeps it.
#include <gtest/gtest.h>

#include <string>

#include "map/synthetic_scene.h"
#include "stillslam/tracking/tracker.h"

namespace stillslam {
namespace {

constexpr std::size_t kMovers = 850;  // scene points 0..849 of 2500 walk 5 cm a frame (by default)

struct Start {
  int waiting_frames = 0;
  std::uint64_t first_keyframe_frame = 99;
  int first_keyframe_points = 0;
  int first_keyframe_movers = 0;
  double next_offset = -1;  // the frame after the start: pose without the prior from the prediction
  int later_keyframes = 0;     // keyframes after the first
  int later_points = 0;        // map points those made from depth
  int later_movers = 0;        // of those, on walkers
  std::string start_reason;    // the reason of the frame the map started at
};

Start run(int confirm_frames, int trust_frames = 10, int frames = 6, bool keyframe_each_frame = false,
          std::size_t movers = kMovers, double moving_share = 0) {
  test::SyntheticScene scene(2500);
  Map map;
  TrackerOptions options;
  options.init_min_keypoints = 300;
  options.init_unmasked_confirm_frames = confirm_frames;
  options.init_unmasked_trust_frames = trust_frames;
  options.init_unmasked_moving_share = moving_share;
  if (keyframe_each_frame) {  // any untracked close point asks for one, no budget
    options.close_points_tracked_min = 100000;
    options.close_points_untracked_min = 0;
    options.keyframe_budget.per_second = 0;
  }
  Tracker tracker(map, options, {});
  Start out;
  std::vector<std::vector<std::size_t>> scene_point(static_cast<std::size_t>(frames));  // per frame and keypoint
  for (int k = 0; k < frames; ++k) {
    std::vector<std::size_t>& first_point = scene_point[0];
    Frame f = scene.make_frame(static_cast<std::uint64_t>(k), test::pose_at(0.02 * k), &scene_point[static_cast<std::size_t>(k)]);
    const bool started = map.num_keyframes() > 0;
    const TrackingResult r = tracker.track(f);
    if (r.state == TrackingState::NotInitialized) ++out.waiting_frames;
    if (!started && map.num_keyframes() > 0) {
      out.start_reason = r.reason;
      const KeyFramePtr kf = map.keyframes().front();
      out.first_keyframe_frame = kf->frame_id();
      for (std::size_t i = 0; kf->frame_id() == 0 && i < kf->size(); ++i) {
        if (!kf->map_point(i)) continue;
        ++out.first_keyframe_points;
        out.first_keyframe_movers += first_point[i] < movers ? 1 : 0;
      }
    }
    if (k == confirm_frames + 1) out.next_offset = r.motion_prior.offset;
    for (std::size_t i = 0; i < movers; ++i) scene.move_point(i, Eigen::Vector3d(0.05, 0, 0));
  }
  for (const KeyFramePtr& kf : map.keyframes()) {
    if (kf->frame_id() == 0) continue;
    ++out.later_keyframes;
    for (std::size_t i = 0; i < kf->size(); ++i) {
      const MapPointPtr& mp = kf->map_point(i);
      if (!mp || mp->first_keyframe_id() != kf->id()) continue;
      ++out.later_points;
      out.later_movers += scene_point[kf->frame_id()][i] < movers ? 1 : 0;
    }
  }
  return out;
}

TEST(TrackerStartUnmasked, TheFirstKeyFrameTakesNoWalkersPoints) {
  const Start checked = run(3);
  EXPECT_EQ(checked.waiting_frames, 3);
  EXPECT_EQ(checked.first_keyframe_frame, 0u);
  EXPECT_EQ(checked.first_keyframe_movers, 0);
  // The start frame was tracked 3 frames from the first: the next frame's
  // prediction uses the motion of one frame (3 frames' would be 4 cm off).
  EXPECT_GE(checked.next_offset, 0);
  EXPECT_LT(checked.next_offset, 0.002);

  const Start unchecked = run(0);  // the map starts at the first frame with depth
  EXPECT_EQ(unchecked.waiting_frames, 0);
  EXPECT_EQ(unchecked.first_keyframe_frame, 0u);
  EXPECT_GT(unchecked.first_keyframe_movers, 0.25 * unchecked.first_keyframe_points);
  // Most static points are kept: those matched as inliers in all 3 frames
  // (the camera moves 6 cm, some leave the view).
  const int statics = unchecked.first_keyframe_points - unchecked.first_keyframe_movers;
  EXPECT_GT(checked.first_keyframe_points, 0.6 * statics);
}

TEST(TrackerStartUnmasked, TheFramesAfterTheStartTakeNoWalkersPoints) {
  // 14 frames: the start at frame 3, then 10 frames in the trust window.
  const Start trusted = run(3, 10, 14, true);
  const Start check_only = run(3, 0, 14, true);
  ASSERT_GT(trusted.later_keyframes, 0);
  ASSERT_GT(check_only.later_keyframes, 0);
  // Without the window the keyframes after the start make points on the walkers.
  EXPECT_GT(check_only.later_movers, 0.2 * check_only.later_points);
  // With it, the static ones only (the previous frame saw them in place).
  EXPECT_GT(trusted.later_points, 0);
  EXPECT_EQ(trusted.later_movers, 0);
}

TEST(TrackerStartUnmasked, TheGateKeepsTheFirstKeyFrameWholeWhereLittleMoves) {
  // Nothing moves: with the gate the first keyframe holds every point a start
  // without the check makes; the check alone keeps only the confirmed ones.
  const Start whole = run(0, 10, 6, false, 0);
  const Start gated = run(3, 10, 6, false, 0, 0.05);
  const Start filtered = run(3, 10, 6, false, 0, 0);
  EXPECT_EQ(gated.waiting_frames, 3);
  EXPECT_EQ(gated.first_keyframe_frame, 0u);
  EXPECT_EQ(gated.first_keyframe_points, whole.first_keyframe_points);
  EXPECT_LT(filtered.first_keyframe_points, whole.first_keyframe_points);
  EXPECT_NE(gated.start_reason.find("0 of "), std::string::npos) << gated.start_reason;
  EXPECT_NE(gated.start_reason.find("kept whole"), std::string::npos) << gated.start_reason;

  // 50 of 2500 points walk (about 2 % of the matched ones): under a 5 % gate
  // the walkers stay in with the rest; under a 1 % gate they are left out.
  const Start few_whole = run(0, 10, 6, false, 50);
  const Start few_gated = run(3, 10, 6, false, 50, 0.05);
  const Start few_filtered = run(3, 10, 6, false, 50, 0.01);
  EXPECT_GT(few_whole.first_keyframe_movers, 10);
  EXPECT_EQ(few_gated.first_keyframe_points, few_whole.first_keyframe_points);
  EXPECT_EQ(few_gated.first_keyframe_movers, few_whole.first_keyframe_movers);
  EXPECT_EQ(few_filtered.first_keyframe_movers, 0);
  EXPECT_NE(few_filtered.start_reason.find("left out"), std::string::npos) << few_filtered.start_reason;

  // A third of the view walks: the gate lets the check filter, no walker gets in.
  const Start walkers = run(3, 10, 6, false, kMovers, 0.05);
  EXPECT_EQ(walkers.first_keyframe_movers, 0);
  EXPECT_GT(walkers.first_keyframe_points, 0);
}

}  // namespace
}  // namespace stillslam
