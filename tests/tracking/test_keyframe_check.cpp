// KeyframeCheck (tracking/keyframe_check.h): a keyframe made under a carried
// mask is in use at once and checked when its frame's own mask arrives: its
// own points inside the mask culled, its matches to older points there
// unlinked, and with cull_new_points the points made after it culled too.
#include <gtest/gtest.h>

#include "map/synthetic_scene.h"
#include "stillslam/map/map.h"
#include "stillslam/tracking/keyframe_check.h"
#include "stillslam/tracking/keypoint_pixels.h"

namespace stillslam {
namespace {

// Keyframe `checked` (frame f1) sees: old points (made by kf0, also seen by
// two more keyframes) at keypoints i % 3 == 0, its own new points at
// i % 3 == 1, and points a later keyframe made at i % 3 == 2.
struct Scene {
  test::SyntheticScene scene{400};
  Map map;
  Frame f1;
  KeyFramePtr checked;
  std::vector<MapPointPtr> points;  // per keypoint of f1
  cv::Mat1b mask;                   // the left quarter
  int inside[3] = {0, 0, 0};        // keypoints inside the mask per kind

  Scene() {
    Frame f0 = scene.make_frame(0, test::pose_at(0));
    f0.set_pose(test::pose_at(0));
    const KeyFramePtr kf0 = map.create_keyframe(f0);
    const KeyFramePtr kf0b = map.create_keyframe(f0);
    const KeyFramePtr kf0c = map.create_keyframe(f0);
    f1 = scene.make_frame(1, test::pose_at(0));
    f1.set_pose(test::pose_at(0));
    checked = map.create_keyframe(f1);
    const KeyFramePtr later = map.create_keyframe(f1);
    points.resize(f1.size());
    for (std::size_t i = 0; i < f1.size(); ++i) {
      KeyFrame* first = i % 3 == 0 ? kf0.get() : i % 3 == 1 ? checked.get() : later.get();
      MapPointPtr mp = map.create_map_point(*f1.unproject(i), first);
      mp->add_observation(checked.get(), i);
      checked->set_map_point(i, mp);
      for (KeyFrame* other : {kf0.get(), kf0b.get(), kf0c.get(), later.get()}) {
        if (i % 3 == 1 && other != later.get()) continue;
        mp->add_observation(other, i);
        other->set_map_point(i, mp);
      }
      points[i] = mp;
    }
    const cv::Size size(f1.setup().camera.width(), f1.setup().camera.height());
    mask = cv::Mat1b::zeros(size);
    mask(cv::Rect(0, 0, size.width / 4, size.height)).setTo(255);
    for (std::size_t i = 0; i < f1.size(); ++i) inside[i % 3] += on(i);
  }
  bool on(std::size_t i) const {
    const cv::Point2f p = f1.keypoints_raw()[i].pt;
    return mask(cv::Point(cvRound(p.x), cvRound(p.y))) != 0;
  }
};

TEST(KeyframeCheck, CullsItsOwnPointsInsideItsMaskAndUnlinksTheOthers) {
  Scene s;
  ASSERT_GT(s.inside[0], 10);
  ASSERT_GT(s.inside[1], 10);
  ASSERT_GT(s.inside[2], 10);
  KeyframeCheck check;
  check.add(s.checked, keypoint_pixels(s.f1));
  EXPECT_EQ(check.check(7, {s.mask}).checked, 0);  // its input frame not known yet: waits
  EXPECT_EQ(check.assign(7), 1);
  EXPECT_EQ(check.assign(8), 0);  // assigned once
  EXPECT_EQ(check.check(6, {s.mask}).checked, 0);  // an older frame's mask: nothing
  EXPECT_EQ(check.size(), 1u);
  const KeyframeCheckResult r = check.check(7, {s.mask});
  EXPECT_EQ(r.checked, 1);
  EXPECT_EQ(r.culled, s.inside[1]);
  EXPECT_EQ(r.unlinked, s.inside[0] + s.inside[2]);
  EXPECT_EQ(r.unchecked, 0);
  EXPECT_TRUE(check.empty());
  for (std::size_t i = 0; i < s.f1.size(); ++i) {
    const bool on = s.on(i);
    EXPECT_EQ(s.points[i]->is_bad(), i % 3 == 1 && on) << i;
    EXPECT_EQ(s.checked->map_point(i) == nullptr, on) << i;
  }
}

TEST(KeyframeCheck, WithCullNewPointsThePointsMadeAfterItGoToo) {
  Scene s;
  KeyframeCheck check(true);
  check.add(s.checked, keypoint_pixels(s.f1), 7);  // the index known (the map's first keyframe)
  EXPECT_EQ(check.assign(8), 0);
  const KeyframeCheckResult r = check.check(7, {s.mask});
  EXPECT_EQ(r.checked, 1);
  EXPECT_EQ(r.culled, s.inside[1] + s.inside[2]);
  EXPECT_EQ(r.unlinked, s.inside[0]);
  for (std::size_t i = 0; i < s.f1.size(); ++i) {
    EXPECT_EQ(s.points[i]->is_bad(), i % 3 != 0 && s.on(i)) << i;
    if (i % 3 == 0) {
      EXPECT_EQ(s.points[i]->is_observed_by(s.checked.get()), !s.on(i)) << i;
    }
  }
}

TEST(KeyframeCheck, ANewerMaskDropsItUnchecked) {
  Scene s;
  KeyframeCheck check;
  check.add(s.checked, keypoint_pixels(s.f1));
  EXPECT_EQ(check.assign(5), 1);
  check.add(s.checked, keypoint_pixels(s.f1));
  EXPECT_EQ(check.assign(9), 1);
  // Frame 5's own mask never came (a threaded stage skipped it); frame 8's did.
  const KeyframeCheckResult r = check.check(8, {s.mask});
  EXPECT_EQ(r.unchecked, 1);
  EXPECT_EQ(r.checked, 0);
  EXPECT_EQ(r.culled + r.unlinked, 0);
  for (const MapPointPtr& mp : s.points) EXPECT_FALSE(mp->is_bad());
  EXPECT_EQ(check.size(), 1u);
  EXPECT_EQ(check.drop_all().unchecked, 1);
  EXPECT_TRUE(check.empty());
}

}  // namespace
}  // namespace stillslam
