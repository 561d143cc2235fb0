// KeyframeHold (tracking/keyframe_hold.h): a keyframe made with a carried mask
// reaches local mapping only when its frame's own mask arrives, with its points
// inside that mask removed (its own new points culled, matches to older points
// unlinked); keyframes leave in the order they were made.
#include <gtest/gtest.h>

#include "map/synthetic_scene.h"
#include "stillslam/map/map.h"
#include "stillslam/tracking/keyframe_hold.h"
#include "stillslam/tracking/keypoint_pixels.h"
#include "stillslam/tracking/static_evidence.h"

namespace stillslam {
namespace {

TEST(KeyframeHold, ReleasesAtItsOwnMaskWithoutThePointsInside) {
  test::SyntheticScene scene(400);
  Map map;
  // Frame 0's keyframe made a point of every keypoint; two more keyframes saw
  // them too (so unlinking one observation leaves them good, mono or stereo).
  Frame f0 = scene.make_frame(0, test::pose_at(0));
  f0.set_pose(test::pose_at(0));
  const KeyFramePtr kf0 = map.create_keyframe(f0);
  const KeyFramePtr kf0b = map.create_keyframe(f0);
  const KeyFramePtr kf0c = map.create_keyframe(f0);
  std::vector<MapPointPtr> old_points;
  for (std::size_t i = 0; i < f0.size(); ++i) {
    MapPointPtr mp = map.create_map_point(*f0.unproject(i), kf0.get());
    mp->add_observation(kf0.get(), i);
    mp->add_observation(kf0b.get(), i);
    mp->add_observation(kf0c.get(), i);
    kf0->set_map_point(i, mp);
    kf0b->set_map_point(i, mp);
    kf0c->set_map_point(i, mp);
    old_points.push_back(mp);
  }
  // The held keyframe (input frame 7) matched the old points at even
  // keypoints and made new points at odd ones.
  Frame f1 = scene.make_frame(1, test::pose_at(0));
  f1.set_pose(test::pose_at(0));
  ASSERT_EQ(f1.size(), f0.size());
  for (std::size_t i = 0; i < f1.size(); i += 2) f1.set_map_point(i, old_points[i]);
  const KeyFramePtr held = map.create_keyframe(f1);
  std::vector<MapPointPtr> new_points(f1.size());
  for (std::size_t i = 0; i < f1.size(); ++i) {
    if (held->map_point(i)) old_points[i]->add_observation(held.get(), i);
    if (i % 2 == 0) continue;
    new_points[i] = map.create_map_point(*f1.unproject(i), held.get());
    new_points[i]->add_observation(held.get(), i);
    held->set_map_point(i, new_points[i]);
  }
  const cv::Size size(f1.setup().camera.width(), f1.setup().camera.height());
  cv::Mat1b mask = cv::Mat1b::zeros(size);
  mask(cv::Rect(0, 0, size.width / 4, size.height)).setTo(255);
  int on_old = 0, on_new = 0;
  for (std::size_t i = 0; i < f1.size(); ++i) {
    if (f1.keypoints_raw()[i].pt.x < size.width / 4 - 0.5f) (i % 2 == 0 ? on_old : on_new)++;
  }
  ASSERT_GT(on_old, 10);
  ASSERT_GT(on_new, 10);

  KeyframeHold hold;
  hold.hold(held, keypoint_pixels(f1));
  EXPECT_TRUE(hold.release(7, {mask}).keyframes.empty());  // its input frame not known yet
  EXPECT_EQ(hold.assign(7), 1);
  EXPECT_EQ(hold.assign(8), 0);  // assigned once
  const KeyFramePtr fresh = map.create_keyframe(f1);
  EXPECT_TRUE(hold.pass(fresh).empty());  // behind the held one
  EXPECT_EQ(hold.held(), 1u);
  KeyframeHoldRelease r = hold.release(6, {mask});  // an older frame's mask: nothing leaves
  EXPECT_TRUE(r.keyframes.empty());
  r = hold.release(7, {mask});
  ASSERT_EQ(r.keyframes.size(), 2u);
  EXPECT_EQ(r.keyframes[0], held);
  EXPECT_EQ(r.keyframes[1], fresh);
  EXPECT_EQ(r.culled, on_new);
  EXPECT_EQ(r.unlinked, on_old);
  EXPECT_EQ(r.unchecked, 0);
  EXPECT_TRUE(hold.empty());
  for (std::size_t i = 0; i < f1.size(); ++i) {
    const bool on = mask(cv::Point(cvRound(f1.keypoints_raw()[i].pt.x), cvRound(f1.keypoints_raw()[i].pt.y))) != 0;
    if (i % 2 == 1) {
      EXPECT_EQ(new_points[i]->is_bad(), on) << i;
    } else {
      EXPECT_FALSE(old_points[i]->is_bad()) << i;  // still seen by frame 0's keyframes
      EXPECT_EQ(old_points[i]->is_observed_by(held.get()), !on) << i;
    }
    EXPECT_EQ(held->map_point(i) == nullptr, on) << i;
  }
}

TEST(KeyframeHold, ANewerMaskReleasesUnchecked) {
  test::SyntheticScene scene(200);
  Map map;
  Frame f = scene.make_frame(0, test::pose_at(0));
  f.set_pose(test::pose_at(0));
  const KeyFramePtr kf = map.create_keyframe(f);
  MapPointPtr mp = map.create_map_point(*f.unproject(0), kf.get());
  mp->add_observation(kf.get(), 0);
  kf->set_map_point(0, mp);
  const cv::Size size(f.setup().camera.width(), f.setup().camera.height());
  KeyframeHold hold;
  EXPECT_EQ(hold.pass(kf).size(), 1u);  // nothing held: passes at once
  hold.hold(kf, keypoint_pixels(f));
  EXPECT_EQ(hold.assign(5), 1);
  hold.hold(kf, keypoint_pixels(f));
  EXPECT_EQ(hold.assign(9), 1);
  // Frame 5's own mask never came (a threaded stage skipped it); frame 8's did.
  const KeyframeHoldRelease r = hold.release(8, {cv::Mat1b(size, uchar(255))});
  EXPECT_EQ(r.keyframes.size(), 1u);
  EXPECT_EQ(r.unchecked, 1);
  EXPECT_EQ(r.culled, 0);
  EXPECT_FALSE(mp->is_bad());
  EXPECT_EQ(hold.held(), 1u);
  EXPECT_EQ(hold.release_all().unchecked, 1);
  EXPECT_TRUE(hold.empty());
}


// Segmentation.heldEvidence: the older points a held keyframe matched count
// it in their static-evidence span while it waits (local mapping adds the
// observation only at the release); a match the keyframe's own mask unlinks
// loses it, and without the option nothing changes.
TEST(KeyframeHold, HeldMatchesCountInTheEvidenceSpanUntilTheMaskUnlinksThem) {
  test::SyntheticScene scene(300);
  const cv::Size size(scene.make_frame(0, test::pose_at(0)).setup().camera.width(),
                      scene.make_frame(0, test::pose_at(0)).setup().camera.height());
  cv::Mat1b mask = cv::Mat1b::zeros(size);
  mask(cv::Rect(0, 0, size.width / 4, size.height)).setTo(255);
  const StaticEvidenceOptions evidence;  // a span of 10 frames
  ASSERT_EQ(evidence.min_span_frames, 10);
  for (const bool on : {false, true}) {
    Map map;
    // Frame 0's keyframe made a point of every keypoint: one observation, no span.
    Frame f0 = scene.make_frame(0, test::pose_at(0));
    f0.set_pose(test::pose_at(0));
    const KeyFramePtr kf0 = map.create_keyframe(f0);
    std::vector<MapPointPtr> points;
    for (std::size_t i = 0; i < f0.size(); ++i) {
      MapPointPtr mp = map.create_map_point(*f0.unproject(i), kf0.get());
      mp->add_observation(kf0.get(), i);
      kf0->set_map_point(i, mp);
      points.push_back(mp);
    }
    // Frame 12's keyframe matched all of them and is held.
    Frame f12 = scene.make_frame(12, test::pose_at(0));
    f12.set_pose(test::pose_at(0));
    for (std::size_t i = 0; i < f12.size(); ++i) f12.set_map_point(i, points[i]);
    const KeyFramePtr held = map.create_keyframe(f12);
    KeyframeHold hold(on);
    hold.hold(held, keypoint_pixels(f12));
    int with_evidence = 0;
    for (const MapPointPtr& mp : points) with_evidence += has_static_evidence(*mp, evidence);
    EXPECT_EQ(with_evidence, on ? static_cast<int>(points.size()) : 0);
    for (const MapPointPtr& mp : points) EXPECT_EQ(observation_span_frames(*mp), on ? 12u : 0u);
    // A keyframe queued behind the held one notes its frame too.
    Frame f20 = scene.make_frame(20, test::pose_at(0));
    f20.set_pose(test::pose_at(0));
    f20.set_map_point(1, points[1]);
    EXPECT_TRUE(hold.pass(map.create_keyframe(f20)).empty());
    EXPECT_EQ(points[1]->held_observation_frame(), on ? 20u : 0u);
    EXPECT_EQ(points[2]->held_observation_frame(), on ? 12u : 0u);

    EXPECT_EQ(hold.assign(7), 1);
    const KeyframeHoldRelease r = hold.release(7, {mask});
    ASSERT_EQ(r.keyframes.size(), 2u);
    int inside = 0;
    for (std::size_t i = 0; i < f12.size(); ++i) {
      const cv::Point2f& p = f12.keypoints_raw()[i].pt;
      const bool in = mask(cv::Point(cvRound(p.x), cvRound(p.y))) != 0;
      inside += in;
      // Unlinked inside the mask: neither the held keyframe nor its note (a
      // later keyframe's note stays: point 1 is frame 20's match as well).
      const bool kept = !in || (i == 1);
      EXPECT_EQ(has_static_evidence(*points[i], evidence), on && kept) << i;
      EXPECT_EQ(held->map_point(i) == nullptr, in) << i;
    }
    EXPECT_GT(inside, 10);
    EXPECT_EQ(r.unlinked, inside);
  }
}

}  // namespace
}  // namespace stillslam
