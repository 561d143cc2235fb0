// The frames a map start waits on (the start candidate and the frames that
// confirm it) have no pose while they wait; when the map starts from the
// candidate, TrackingResult::start_frames gives them their poses: the
// candidate at the map's origin (it is the first keyframe), each confirming
// frame at the check's PnP motion from it, with the first keyframe as
// reference and its points as the confirmed matches. Checked against the
// synthetic scene's ground truth, without segmentation (a third of the view
// walking), with segmentation (a person in a corner) and across dropped
// frames; a rejected candidate's frames get no pose and the reason says so.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "map/synthetic_scene.h"
#include "stillslam/tracking/tracker.h"

namespace stillslam {
namespace {

// Position and angle between a start pose (map frame = the first camera) and
// the ground truth relative to the first camera.
struct PoseError {
  double position_m = 1e9, angle_rad = 1e9;
};

PoseError error_against(const Eigen::Isometry3d& T_cam_first, const Eigen::Isometry3d& gt_T_cam_world,
                        const Eigen::Isometry3d& gt_first_T_cam_world) {
  const Eigen::Isometry3d gt = gt_T_cam_world * gt_first_T_cam_world.inverse();
  const Eigen::Isometry3d d = T_cam_first.inverse() * gt;
  return {d.translation().norm(), Eigen::AngleAxisd(d.linear()).angle()};
}

cv::Mat1b corner_mask() {
  cv::Mat1b mask = cv::Mat1b::zeros(480, 640);
  mask(cv::Rect(0, 0, 40, 40)).setTo(255);  // someone in a corner: the start is checked with masks
  return mask;
}

struct Case {
  bool masked = false;
  int confirm_frames = 3;
  int id_step = 1;                 // frame ids this far apart (the frames between dropped)
  std::size_t movers = 0;          // scene points 0..movers-1 walk 5 cm a frame
};

struct Outcome {
  std::vector<TrackingResult> results;
  std::vector<Eigen::Isometry3d> gt;  // per frame, T_cam_world
  std::vector<std::uint64_t> ids;
  std::size_t start = 0;  // the frame the map started at
  KeyFramePtr first_keyframe;
  std::size_t movers = 0;
  std::vector<std::vector<std::size_t>> scene_point;  // per frame and keypoint
};

Outcome run(const Case& c, int frames = 6) {
  test::SyntheticScene scene(2500);
  Map map;
  TrackerOptions options;
  options.init_min_keypoints = 300;
  options.init_confirm_frames = c.confirm_frames;
  options.init_unmasked_confirm_frames = c.confirm_frames;
  Tracker tracker(map, options, {});
  Outcome out;
  out.movers = c.movers;
  out.scene_point.resize(static_cast<std::size_t>(frames));
  for (int k = 0; k < frames; ++k) {
    // Forward and sideways with a turn: the poses differ in every coordinate.
    const double step = c.id_step;
    out.gt.push_back(test::pose_at(0.02 * step * k, 0.005 * step * k, 0.4 * step * k));
    out.ids.push_back(static_cast<std::uint64_t>(k * c.id_step));
    Frame f = scene.make_frame(out.ids.back(), out.gt.back(), &out.scene_point[static_cast<std::size_t>(k)]);
    if (c.masked) f.set_dynamic_mask(corner_mask());
    const bool started = map.num_keyframes() > 0;
    out.results.push_back(tracker.track(f));
    if (!started && map.num_keyframes() > 0) {
      out.start = static_cast<std::size_t>(k);
      out.first_keyframe = map.keyframes().front();
    }
    for (std::size_t i = 0; i < c.movers; ++i) scene.move_point(i, Eigen::Vector3d(0.05 * c.id_step, 0, 0));
  }
  return out;
}

// Every frame before the start is in start_frames, in order, with its pose
// within 0.1 mm and 1e-4 rad of the ground truth, and the confirming frames
// see only the first keyframe's (static) points.
void expect_posed(const Outcome& o, int confirm_frames) {
  ASSERT_TRUE(o.first_keyframe);
  EXPECT_EQ(o.start, static_cast<std::size_t>(confirm_frames));
  for (std::size_t k = 0; k < o.start; ++k) {
    EXPECT_EQ(o.results[k].state, TrackingState::NotInitialized) << k;
    EXPECT_TRUE(o.results[k].start_frames.empty()) << k;
  }
  const TrackingResult& start = o.results[o.start];
  EXPECT_EQ(start.state, TrackingState::Ok) << start.reason;
  EXPECT_NE(start.reason.find("map started at frame 0"), std::string::npos) << start.reason;
  ASSERT_EQ(start.start_frames.size(), o.start);
  for (std::size_t k = 0; k < o.start; ++k) {
    const StartFramePose& s = start.start_frames[k];
    EXPECT_EQ(s.frame.id(), o.ids[k]);
    EXPECT_EQ(s.keyframe, k == 0);
    EXPECT_EQ(s.reference, o.first_keyframe);
    ASSERT_TRUE(s.frame.has_pose()) << k;
    // The pose in the map and relative to the reference agree.
    EXPECT_TRUE(s.frame.T_cam_world().isApprox(s.T_cam_reference * o.first_keyframe->T_cam_world(), 1e-12));
    const PoseError e = error_against(s.frame.T_cam_world(), o.gt[k], o.gt[0]);
    EXPECT_LT(e.position_m, 1e-4) << "frame " << k;
    EXPECT_LT(e.angle_rad, 1e-4) << "frame " << k;
    if (k == 0) continue;
    // It moved: a pose left at the origin would be centimetres off.
    EXPECT_GT(error_against(Eigen::Isometry3d::Identity(), o.gt[k], o.gt[0]).position_m, 0.015);
    int seen = 0, movers = 0;
    for (std::size_t i = 0; i < s.frame.size(); ++i) {
      const MapPointPtr& mp = s.frame.map_point(i);
      if (!mp) continue;
      ++seen;
      // Each is a first-keyframe point, observed where it projects in the frame.
      EXPECT_EQ(mp->observations().count(o.first_keyframe.get()), 1u);
      const Eigen::Vector3d in_cam = s.frame.T_cam_world() * mp->position();
      const Eigen::Vector2d uv = s.frame.setup().camera.project(in_cam);
      EXPECT_LT((uv - Eigen::Vector2d(s.frame.keypoint(i).pt.x, s.frame.keypoint(i).pt.y)).norm(), 0.5);
      movers += o.scene_point[k][i] < o.movers ? 1 : 0;
    }
    EXPECT_GT(seen, 300) << "frame " << k;
    EXPECT_EQ(movers, 0) << "frame " << k;
  }
}

TEST(TrackerStartPoses, WithoutSegmentationTheWaitedFramesArePosedAtTheirMotion) {
  const Outcome static_view = run({.masked = false, .confirm_frames = 3});
  expect_posed(static_view, 3);
  // A third of the view walks: the check leaves the walkers out and the
  // waited frames still get the camera's motion, not the walkers'.
  const Outcome walkers = run({.masked = false, .confirm_frames = 3, .movers = 850});
  expect_posed(walkers, 3);
}

TEST(TrackerStartPoses, WithSegmentationTheWaitedFramesArePosedAtTheirMotion) {
  expect_posed(run({.masked = true, .confirm_frames = 2}), 2);
  expect_posed(run({.masked = true, .confirm_frames = 1}), 1);
}

TEST(TrackerStartPoses, AcrossDroppedFramesTheWaitedFramesArePosed) {
  // Frame ids 3 apart (--realtime dropped the two between): 6 cm and 1.2
  // degrees of yaw between neighbours.
  expect_posed(run({.masked = false, .confirm_frames = 3, .id_step = 3}), 3);
  expect_posed(run({.masked = true, .confirm_frames = 2, .id_step = 3}), 2);
}

TEST(TrackerStartPoses, WithoutTheCheckNoFrameWaits) {
  const Outcome o = run({.masked = false, .confirm_frames = 0}, 3);
  ASSERT_TRUE(o.first_keyframe);
  EXPECT_EQ(o.start, 0u);
  EXPECT_EQ(o.results[0].reason, "initialized");
  for (const TrackingResult& r : o.results) EXPECT_TRUE(r.start_frames.empty());
}

TEST(TrackerStartPoses, ARejectedCandidateAndItsConfirmingFramesGetNoPose) {
  // Frames 0 and 1 see the scene, frame 2 a different one (the view jumps):
  // the check rejects frame 0's candidate, frame 2 becomes the candidate and
  // frames 3-5 (seeing frame 2's scene) confirm it. Frames 0 and 1 get no pose.
  test::SyntheticScene scene(2500), other(2500, 11);
  Map map;
  TrackerOptions options;
  options.init_min_keypoints = 300;
  options.init_unmasked_confirm_frames = 3;
  Tracker tracker(map, options, {});
  std::vector<TrackingResult> results;
  for (int k = 0; k < 6; ++k) {
    const test::SyntheticScene& s = k < 2 ? scene : other;
    Frame f = s.make_frame(static_cast<std::uint64_t>(k), test::pose_at(0.02 * k));
    results.push_back(tracker.track(f));
  }
  EXPECT_EQ(results[1].state, TrackingState::NotInitialized);
  EXPECT_NE(results[1].reason.find("confirmed by 1 of 3"), std::string::npos) << results[1].reason;
  EXPECT_EQ(results[2].state, TrackingState::NotInitialized);
  EXPECT_NE(results[2].reason.find("the start candidate (frame 0) and the 1 frame that confirmed it (to frame 1) get "
                                   "no pose"),
            std::string::npos)
      << results[2].reason;
  ASSERT_EQ(results[5].state, TrackingState::Ok) << results[5].reason;
  EXPECT_NE(results[5].reason.find("map started at frame 2"), std::string::npos) << results[5].reason;
  ASSERT_EQ(results[5].start_frames.size(), 3u);
  EXPECT_EQ(results[5].start_frames[0].frame.id(), 2u);
  EXPECT_EQ(results[5].start_frames[1].frame.id(), 3u);
  EXPECT_EQ(results[5].start_frames[2].frame.id(), 4u);
  for (int k = 0; k < 5; ++k) EXPECT_TRUE(results[static_cast<std::size_t>(k)].start_frames.empty());
}

}  // namespace
}  // namespace stillslam
