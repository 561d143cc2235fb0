// A map start without segmentation in a view a third of which walks: the
// first keyframe waits for the next frames' geometric check and takes none of
// the walkers' points; the velocity after the start is per frame; in the
// frames after the start the keyframes take no walkers' points either
// (tracking/start_evidence.h).
#include <gtest/gtest.h>

#include "map/synthetic_scene.h"
#include "stillslam/tracking/tracker.h"

namespace stillslam {
namespace {

constexpr std::size_t kMovers = 850;  // scene points 0..849 of 2500 walk 5 cm a frame

struct Start {
  int waiting_frames = 0;
  std::uint64_t first_keyframe_frame = 99;
  int first_keyframe_points = 0;
  int first_keyframe_movers = 0;
  double next_offset = -1;  // the frame after the start: pose without the prior from the prediction
  int later_keyframes = 0;     // keyframes after the first
  int later_points = 0;        // map points those made from depth
  int later_movers = 0;        // of those, on walkers
};

Start run(int confirm_frames, int trust_frames = 10, int frames = 6, bool keyframe_each_frame = false) {
  test::SyntheticScene scene(2500);
  Map map;
  TrackerOptions options;
  options.init_min_keypoints = 300;
  options.init_unmasked_confirm_frames = confirm_frames;
  options.init_unmasked_trust_frames = trust_frames;
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
      const KeyFramePtr kf = map.keyframes().front();
      out.first_keyframe_frame = kf->frame_id();
      for (std::size_t i = 0; kf->frame_id() == 0 && i < kf->size(); ++i) {
        if (!kf->map_point(i)) continue;
        ++out.first_keyframe_points;
        out.first_keyframe_movers += first_point[i] < kMovers ? 1 : 0;
      }
    }
    if (k == confirm_frames + 1) out.next_offset = r.motion_prior.offset;
    for (std::size_t i = 0; i < kMovers; ++i) scene.move_point(i, Eigen::Vector3d(0.05, 0, 0));
  }
  for (const KeyFramePtr& kf : map.keyframes()) {
    if (kf->frame_id() == 0) continue;
    ++out.later_keyframes;
    for (std::size_t i = 0; i < kf->size(); ++i) {
      const MapPointPtr& mp = kf->map_point(i);
      if (!mp || mp->first_keyframe_id() != kf->id()) continue;
      ++out.later_points;
      out.later_movers += scene_point[kf->frame_id()][i] < kMovers ? 1 : 0;
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

}  // namespace
}  // namespace stillslam
