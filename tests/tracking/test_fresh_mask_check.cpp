// FreshMaskCheck (tracking/fresh_mask_check.h): when a segmented frame's own
// mask arrives, the map points it saw inside a dynamic instance are culled,
// the others stay, and the frame (and older ones) are forgotten.
#include <gtest/gtest.h>

#include "map/synthetic_scene.h"
#include "stillslam/map/map.h"
#include "stillslam/tracking/fresh_mask_check.h"

namespace stillslam {
namespace {

struct Seen {
  Map map;
  Frame frame;
  std::vector<MapPointPtr> points;  // one per keypoint, each observed by one keyframe
};

// A frame of the synthetic scene whose every keypoint saw a map point.
void make_seen(Seen& s, std::uint64_t id) {
  test::SyntheticScene scene(400);
  s.frame = scene.make_frame(id, test::pose_at(0));
  s.frame.set_pose(test::pose_at(0));
  const KeyFramePtr kf = s.map.create_keyframe(s.frame);
  for (std::size_t i = 0; i < s.frame.size(); ++i) {
    MapPointPtr mp = s.map.create_map_point(*s.frame.unproject(i), kf.get());
    mp->add_observation(kf.get(), i);
    kf->set_map_point(i, mp);
    s.frame.set_map_point(i, mp);
    s.points.push_back(mp);
  }
}

TEST(FreshMaskCheck, CullsThePointsSeenOnAnInstanceOnly) {
  Seen s;
  make_seen(s, 12);
  ASSERT_GT(s.frame.size(), 100u);
  const cv::Size size(s.frame.setup().camera.width(), s.frame.setup().camera.height());
  // Two instances: the left quarter and a 40x40 square at the bottom right.
  std::vector<cv::Mat1b> instances(2);
  instances[0] = cv::Mat1b::zeros(size);
  instances[1] = cv::Mat1b::zeros(size);
  instances[0](cv::Rect(0, 0, size.width / 4, size.height)).setTo(255);
  const cv::Rect square(size.width - 40, size.height - 40, 40, 40);
  instances[1](square).setTo(255);
  int expected = 0;
  for (std::size_t i = 0; i < s.frame.size(); ++i) {
    const cv::Point p(cvRound(s.frame.keypoints_raw()[i].pt.x), cvRound(s.frame.keypoints_raw()[i].pt.y));
    expected += p.x < size.width / 4 || square.contains(p);
  }
  ASSERT_GT(expected, 10);

  FreshMaskCheck check;
  check.remember(12, s.frame);
  EXPECT_TRUE(check.remembers(12));
  EXPECT_EQ(check.apply(11, instances), 0);  // an older frame's mask: nothing of frame 12
  EXPECT_TRUE(check.remembers(12));
  EXPECT_EQ(check.apply(12, instances), expected);
  EXPECT_FALSE(check.remembers(12));
  int bad = 0;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const cv::Point p(cvRound(s.frame.keypoints_raw()[i].pt.x), cvRound(s.frame.keypoints_raw()[i].pt.y));
    const bool on = p.x < size.width / 4 || square.contains(p);
    EXPECT_EQ(s.points[i]->is_bad(), on) << i;
    bad += s.points[i]->is_bad();
  }
  EXPECT_EQ(bad, expected);
  EXPECT_EQ(check.apply(12, instances), 0);  // forgotten: applied once
}

TEST(FreshMaskCheck, ANewerMaskForgetsOlderFramesWithoutCulling) {
  Seen s;
  make_seen(s, 5);
  const cv::Size size(s.frame.setup().camera.width(), s.frame.setup().camera.height());
  FreshMaskCheck check;
  check.remember(5, s.frame);
  check.remember(8, s.frame);
  // Frame 5's own mask never came (the stage skipped it); frame 9's did.
  EXPECT_EQ(check.apply(9, {cv::Mat1b(size, uchar(255))}), 0);
  EXPECT_FALSE(check.remembers(5));
  EXPECT_FALSE(check.remembers(8));
  for (const MapPointPtr& mp : s.points) EXPECT_FALSE(mp->is_bad());
  check.remember(10, s.frame);
  check.clear();
  EXPECT_EQ(check.apply(10, {cv::Mat1b(size, uchar(255))}), 0);
}

}  // namespace
}  // namespace stillslam
