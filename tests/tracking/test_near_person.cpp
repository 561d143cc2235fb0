// Keyframe depth points near a carried person (tracking/near_person.h,
// Segmentation.nearPerson*): under a carried mask, a keypoint within the
// age-grown radius of a carried instance and within the depth band of its
// median depth makes no new depth point; the others are unaffected.
#include <gtest/gtest.h>

#include <cmath>

#include "map/synthetic_scene.h"
#include "stillslam/core/option_check.h"
#include "stillslam/tracking/near_person.h"
#include "stillslam/tracking/tracker.h"

namespace stillslam {
namespace {

const cv::Rect kPerson(260, 140, 120, 200);  // the carried instance, at 3 m
constexpr float kPersonDepth = 3.0f;

std::vector<CarriedInstance> person(float depth = kPersonDepth) {
  cv::Mat1b mask = cv::Mat1b::zeros(480, 640);
  mask(kPerson).setTo(255);
  return {CarriedInstance{mask, depth}};
}

// Euclidean distance from a pixel to the nearest pixel of kPerson.
double distance_to_person(const cv::Point2f& pt) {
  const cv::Point p(cvRound(pt.x), cvRound(pt.y));
  const int dx = std::max({kPerson.x - p.x, 0, p.x - (kPerson.x + kPerson.width - 1)});
  const int dy = std::max({kPerson.y - p.y, 0, p.y - (kPerson.y + kPerson.height - 1)});
  return std::hypot(dx, dy);
}

NearPersonOptions on() {
  NearPersonOptions o;
  o.px_per_frame = 5;
  o.max_px = 40;
  o.depth_band_m = 0.5;
  return o;
}

TEST(NearPerson, KeypointsNearACarriedInstanceAtItsDepthOnly) {
  test::SyntheticScene scene(3000);
  Frame frame = scene.make_frame(0, test::pose_at(0));
  frame.set_carried_instances(person());
  const NearPersonOptions options = on();
  for (int age : {2, 4, 6, 12}) {
    frame.set_mask_age(age);
    const double radius = options.radius_px(age);
    EXPECT_DOUBLE_EQ(radius, std::min(40.0, 5.0 * age));
    const std::vector<char> near = near_carried_person(frame, options);
    ASSERT_EQ(near.size(), frame.size());
    int flagged = 0, expected_near = 0, expected_far = 0, checked = 0;
    for (std::size_t i = 0; i < frame.size(); ++i) {
      const double d = distance_to_person(frame.keypoints_raw()[i].pt);
      const double dz = std::abs(frame.depth(i) - kPersonDepth);
      flagged += near[i];
      // Away from the radius's and the band's edges the answer is certain
      // (the distance transform is approximate by a fraction of a pixel).
      if (d <= radius - 1.5 && dz <= 0.49) {
        EXPECT_TRUE(near[i]) << "age " << age << " keypoint " << i << " at " << d << " px, " << dz << " m";
        ++expected_near;
        ++checked;
      } else if (d > radius + 1.5 || dz > 0.51) {
        EXPECT_FALSE(near[i]) << "age " << age << " keypoint " << i << " at " << d << " px, " << dz << " m";
        ++expected_far;
        ++checked;
      }
    }
    EXPECT_GT(expected_near, 20) << age;
    EXPECT_GT(expected_far, 1000) << age;
    EXPECT_GE(checked, static_cast<int>(frame.size()) - 30) << age;
    EXPECT_GE(flagged, expected_near) << age;
    EXPECT_LE(flagged, static_cast<int>(frame.size()) - expected_far) << age;
  }
  // The radius grows with the age up to the cap.
  frame.set_mask_age(1);
  const auto count = [&](const NearPersonOptions& o) {
    const std::vector<char> near = near_carried_person(frame, o);
    return std::count(near.begin(), near.end(), 1);
  };
  const long at1 = count(options);
  frame.set_mask_age(6);
  const long at6 = count(options);
  frame.set_mask_age(8);
  const long at8 = count(options);
  frame.set_mask_age(30);
  const long at30 = count(options);
  EXPECT_LT(at1, at6);
  EXPECT_EQ(at8, at30);  // 40 px from age 8 on
}

TEST(NearPerson, NothingAtAgeZeroOffOrWithoutTheInstancesDepth) {
  test::SyntheticScene scene(3000);
  Frame frame = scene.make_frame(0, test::pose_at(0));
  frame.set_carried_instances(person());
  frame.set_mask_age(5);
  const auto count = [](const std::vector<char>& v) { return std::count(v.begin(), v.end(), 1); };
  ASSERT_GT(count(near_carried_person(frame, on())), 20);
  NearPersonOptions off = on();
  off.px_per_frame = 0;
  EXPECT_EQ(count(near_carried_person(frame, off)), 0);
  frame.set_mask_age(0);
  EXPECT_EQ(count(near_carried_person(frame, on())), 0);
  frame.set_mask_age(5);
  frame.set_carried_instances(person(0.f));  // depth unknown
  EXPECT_EQ(count(near_carried_person(frame, on())), 0);
  frame.set_carried_instances({});
  EXPECT_EQ(count(near_carried_person(frame, on())), 0);
}

TEST(NearPerson, OptionsCheckNamesTheField) {
  NearPersonOptions o = on();
  EXPECT_NO_THROW(o.check());
  o.depth_band_m = 0;
  EXPECT_THROW(o.check(), OptionError);
  o = on();
  o.px_per_frame = -1;
  EXPECT_THROW(o.check(), OptionError);
}

// The map's first keyframe, made from a frame under a carried mask: with the
// rule on, no map point near the person at its depth; the rest as without it.
TEST(NearPerson, TheTrackerMakesNoDepthPointNearTheCarriedPerson) {
  test::SyntheticScene scene(2500);
  const auto run = [&](bool rule, std::size_t* skipped, bool at_start = true) {
    Map map;
    TrackerOptions options;
    options.init_min_keypoints = 300;
    if (rule) options.near_person = on();
    options.near_person.at_start = at_start;
    Tracker tracker(map, options, {});
    // Unmasked frames (carried instances only): the start check's 3 frames confirm frame 0, the first keyframe.
    for (std::uint64_t i = 0; i < 4; ++i) {
      Frame f = scene.make_frame(i, test::pose_at(0.01 * static_cast<double>(i)));
      f.set_mask_age(4);  // radius 20 px
      f.set_carried_instances(person());
      tracker.track(f);
    }
    *skipped = tracker.near_person_skipped();
    EXPECT_EQ(map.num_keyframes(), 1u);
    return map.num_keyframes() ? map.keyframes().front() : nullptr;
  };
  std::size_t skipped_on = 0, skipped_off = 0;
  const KeyFramePtr with = run(true, &skipped_on), without = run(false, &skipped_off);
  EXPECT_EQ(skipped_off, 0u);
  ASSERT_TRUE(with && without);
  ASSERT_EQ(with->size(), without->size());
  Frame frame0 = scene.make_frame(0, test::pose_at(0));
  frame0.set_mask_age(4);
  frame0.set_carried_instances(person());
  const std::vector<char> near = near_carried_person(frame0, on());
  std::size_t near_with_point_without = 0, kept_elsewhere = 0, elsewhere = 0;
  for (std::size_t i = 0; i < without->size(); ++i) {
    if (near[i]) {
      EXPECT_FALSE(with->map_point(i)) << i;
      near_with_point_without += without->map_point(i) != nullptr;
    } else if (without->map_point(i)) {
      ++elsewhere;
      kept_elsewhere += with->map_point(i) != nullptr;
    }
  }
  EXPECT_GT(near_with_point_without, 20u);
  EXPECT_EQ(skipped_on, near_with_point_without);
  EXPECT_EQ(kept_elsewhere, elsewhere);
  // Segmentation.nearPersonAtStart 0: the first keyframe keeps every point, as without the rule.
  std::size_t skipped_not_at_start = 0;
  const KeyFramePtr not_at_start = run(true, &skipped_not_at_start, false);
  ASSERT_TRUE(not_at_start);
  EXPECT_EQ(skipped_not_at_start, 0u);
  std::size_t same = 0, points = 0;
  for (std::size_t i = 0; i < without->size(); ++i) {
    points += without->map_point(i) != nullptr;
    same += (without->map_point(i) != nullptr) && (not_at_start->map_point(i) != nullptr);
    EXPECT_EQ(not_at_start->map_point(i) != nullptr, without->map_point(i) != nullptr) << i;
  }
  EXPECT_EQ(same, points);
}

}  // namespace
}  // namespace stillslam
