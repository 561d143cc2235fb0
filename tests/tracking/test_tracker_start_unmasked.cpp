// A map start without segmentation in a view a third of which walks: the
// first keyframe waits for the next frames' geometric check and takes none of
// the walkers' points; the velocity after the start is per frame.
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
};

Start run(int confirm_frames) {
  test::SyntheticScene scene(2500);
  Map map;
  TrackerOptions options;
  options.init_min_keypoints = 300;
  options.init_unmasked_confirm_frames = confirm_frames;
  Tracker tracker(map, options, {});
  Start out;
  std::vector<std::size_t> first_point;  // scene point of each keypoint of frame 0
  for (int k = 0; k < 6; ++k) {
    Frame f = scene.make_frame(static_cast<std::uint64_t>(k), test::pose_at(0.02 * k), k == 0 ? &first_point : nullptr);
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

}  // namespace
}  // namespace stillslam
