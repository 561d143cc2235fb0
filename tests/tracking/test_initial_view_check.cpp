// The first keyframe's check against the next frame, on synthetic scenes in
// which chosen points move between the two frames.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "map/synthetic_scene.h"
#include "stillslam/core/option_check.h"
#include "stillslam/tracking/initial_view_check.h"

namespace stillslam {
namespace {

cv::Mat1b empty_mask() { return cv::Mat1b(480, 640, std::uint8_t{0}); }

// Points whose index is below `share` of the scene: a "person" (they are
// spread over the whole view, so their share of the matches is about `share`).
std::vector<std::size_t> first_points(const test::SyntheticScene& scene, double share) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < static_cast<std::size_t>(share * scene.points().size()); ++i) out.push_back(i);
  return out;
}

struct TwoFrames {
  Frame first, next;
  std::vector<std::size_t> first_point;  // scene point of each first-frame keypoint
};

TwoFrames two_frames(test::SyntheticScene& scene, const std::vector<std::size_t>& movers, double move_m) {
  TwoFrames t;
  t.first = scene.make_frame(0, test::pose_at(0), &t.first_point);
  t.first.set_dynamic_mask(empty_mask());
  for (std::size_t i : movers) scene.move_point(i, Eigen::Vector3d(move_m, 0, 0));
  t.next = scene.make_frame(1, test::pose_at(0.02, 0, 1));
  t.next.set_dynamic_mask(empty_mask());
  return t;
}

TEST(InitialViewCheck, AcceptsAStaticViewWhole) {
  test::SyntheticScene scene(1500);
  const TwoFrames t = two_frames(scene, {}, 0);
  const InitialViewCheck c = check_initial_view(t.first, t.next, {});
  EXPECT_TRUE(c.accepted) << c.reason;
  EXPECT_GT(c.matches, 500);
  EXPECT_EQ(c.moving, 0);
  EXPECT_EQ(std::count(c.keep.begin(), c.keep.end(), true), static_cast<long>(t.first.size()));
  // The returned motion is the next frame's pose relative to the first (at the origin).
  const Eigen::Isometry3d truth = test::pose_at(0.02, 0, 1);
  EXPECT_LT((c.T_next_first.translation() - truth.translation()).norm(), 1e-3);
  EXPECT_LT(Eigen::AngleAxisd(c.T_next_first.linear().transpose() * truth.linear()).angle(), 1e-3);
}

TEST(InitialViewCheck, RejectsAViewWhereMuchMovesUnmasked) {
  test::SyntheticScene scene(1500);
  const TwoFrames t = two_frames(scene, first_points(scene, 0.35), 0.05);
  const InitialViewCheck c = check_initial_view(t.first, t.next, {});
  EXPECT_FALSE(c.accepted);
  EXPECT_NEAR(static_cast<double>(c.moving) / c.matches, 0.35, 0.05);
  EXPECT_NE(c.reason.find("move"), std::string::npos) << c.reason;
}

TEST(InitialViewCheck, LeavesOutAFewMovingPoints) {
  test::SyntheticScene scene(1500);
  const std::vector<std::size_t> movers = first_points(scene, 0.1);
  const TwoFrames t = two_frames(scene, movers, 0.1);
  const InitialViewCheck c = check_initial_view(t.first, t.next, {});
  ASSERT_TRUE(c.accepted) << c.reason;
  int moving_kept = 0, static_dropped = 0;
  for (std::size_t k = 0; k < t.first.size(); ++k) {
    const bool moves = t.first_point[k] < movers.size();
    moving_kept += moves && c.keep[k] ? 1 : 0;
    static_dropped += !moves && !c.keep[k] ? 1 : 0;
  }
  EXPECT_LE(moving_kept, 2);  // a mover that left the view has no match to judge it by
  EXPECT_EQ(static_dropped, 0);
  EXPECT_GT(c.moving, 40);
}

TEST(InitialViewCheck, LeavesOutWhatTheNextFramesMaskCovers) {
  // The segmenter missed a person in the first frame and found them in the next.
  test::SyntheticScene scene(1500);
  TwoFrames t = two_frames(scene, {}, 0);
  cv::Mat1b mask = empty_mask();
  mask.colRange(0, 200).setTo(255);
  t.next.set_dynamic_mask(mask);
  const InitialViewCheck c = check_initial_view(t.first, t.next, {});
  ASSERT_TRUE(c.accepted) << c.reason;
  int kept_left = 0, dropped_right = 0;
  for (std::size_t k = 0; k < t.first.size(); ++k) {
    // The camera moves 2 cm and turns 1 degree: points shift by up to 15 px
    // (those near the left border leave the view: nothing says they move).
    const float x = t.first.keypoint(k).pt.x;
    if (x > 20 && x < 170) kept_left += c.keep[k] ? 1 : 0;
    if (x > 230) dropped_right += c.keep[k] ? 0 : 1;
  }
  EXPECT_EQ(kept_left, 0);
  EXPECT_EQ(dropped_right, 0);
}

// Without segmentation (no masks at all) a third of the view moves: the
// start is accepted, and only the matched points that agree with the camera
// motion are kept and confirmed.
TEST(InitialViewCheck, UnmaskedKeepsOnlyConfirmedStaticPoints) {
  test::SyntheticScene scene(1500);
  const std::vector<std::size_t> movers = first_points(scene, 0.35);
  std::vector<std::size_t> first_point;
  const Frame first = scene.make_frame(0, test::pose_at(0), &first_point);
  for (std::size_t i : movers) scene.move_point(i, Eigen::Vector3d(0.05, 0, 0));
  const Frame next = scene.make_frame(1, test::pose_at(0.02, 0, 1));
  const InitialViewCheck c = check_initial_view(first, next, {});
  ASSERT_TRUE(c.accepted) << c.reason;
  EXPECT_NEAR(static_cast<double>(c.moving) / c.matches, 0.35, 0.05);
  int moving_kept = 0, static_kept = 0, statics = 0;
  for (std::size_t k = 0; k < first.size(); ++k) {
    const bool moves = first_point[k] < movers.size();
    const bool kept = c.keep[k] && c.confirmed[k];  // the tracker's rule without masks
    moving_kept += moves && kept ? 1 : 0;
    static_kept += !moves && kept ? 1 : 0;
    statics += moves ? 0 : 1;
  }
  EXPECT_EQ(moving_kept, 0);  // a mover that left the view is not kept either
  EXPECT_GT(static_kept, 0.9 * statics);
  // With the masked rule's share the same view is rejected.
  InitialViewCheckOptions strict;
  strict.max_moving_share_unmasked = 0.2;
  EXPECT_FALSE(check_initial_view(first, next, strict).accepted);
}

// The same frame with the keypoints k where shift_px[k] is not zero at
// `level` of the pyramid and moved by shift_px[k] (the error of a keypoint
// detected at a coarse level).
Frame with_levels(const Frame& f, const std::vector<Eigen::Vector2d>& shift_px, int level) {
  std::vector<cv::KeyPoint> kps = f.keypoints();
  for (std::size_t k = 0; k < kps.size(); ++k) {
    if (shift_px[k].isZero()) continue;
    kps[k].octave = level;
    kps[k].pt.x += static_cast<float>(shift_px[k].x());
    kps[k].pt.y += static_cast<float>(shift_px[k].y());
  }
  return Frame(f.id(), f.timestamp(), f.setup_ptr(), kps, kps, f.descriptors().clone(), f.u_right(), f.depth());
}

// Without masks a match finds its point moving only beyond a bound scaled
// by its keypoints' pyramid level, but confirms it only within the level-0
// bound: static points detected at level 6 (scale 2.99) and 2.5 px off in the
// next frame are neither confirmed nor left out (another frame may confirm
// them), the same offset at level 0 leaves them out, and movers are left out
// at any level; a moving factor widens the moving bound alone.
TEST(InitialViewCheck, UnmaskedMovingBoundScalesWithThePyramidLevel) {
  test::SyntheticScene scene(1500);
  const std::vector<std::size_t> movers = first_points(scene, 0.2);
  std::vector<std::size_t> first_point, next_point;
  const Frame first = scene.make_frame(0, test::pose_at(0), &first_point);
  for (std::size_t i : movers) scene.move_point(i, Eigen::Vector3d(0.1, 0, 0));  // 10-25 px
  const Frame next_exact = scene.make_frame(1, test::pose_at(0.02, 0, 1), &next_point);
  // Every other point is 2.5 px off in the next frame, each in its own
  // direction (no camera motion fits them); movers are all coarse and off.
  std::vector<Eigen::Vector2d> off(next_exact.size(), Eigen::Vector2d::Zero());
  for (std::size_t k = 0; k < off.size(); ++k) {
    const std::size_t i = next_point[k];
    const double angle = 2.39996 * static_cast<double>(i);  // the golden angle: directions spread evenly
    if (i < movers.size() || i % 2 == 0) off[k] = 2.5 * Eigen::Vector2d(std::cos(angle), std::sin(angle));
  }
  enum Kind { Exact, Off, Mover };
  auto kind = [&](std::size_t k) {
    const std::size_t i = first_point[k];
    return i < movers.size() ? Mover : i % 2 == 0 ? Off : Exact;
  };
  // Per kind: first-frame points, kept (not found moving), confirmed.
  auto count = [&](const InitialViewCheck& c) {
    std::array<std::array<int, 3>, 3> n{};
    for (std::size_t k = 0; k < first.size(); ++k) {
      ++n[kind(k)][0];
      n[kind(k)][1] += c.keep[k] ? 1 : 0;
      n[kind(k)][2] += c.confirmed[k] ? 1 : 0;
    }
    return n;
  };

  InitialViewCheckOptions unit;  // the moving bound: 1 px x the level's scale
  unit.moving_factor_unmasked = 1;
  const InitialViewCheck coarse = check_initial_view(first, with_levels(next_exact, off, 6), unit);
  ASSERT_TRUE(coarse.accepted) << coarse.reason;
  auto n = count(coarse);
  EXPECT_GT(n[Exact][2], 0.9 * n[Exact][0]);
  EXPECT_GT(n[Off][1], 0.9 * n[Off][0]);
  EXPECT_EQ(n[Off][2], 0);
  EXPECT_LT(n[Mover][1], 0.02 * n[Mover][0]);  // a mover that left the view has no match to judge it by
  EXPECT_EQ(n[Mover][2], 0);

  const InitialViewCheck fine = check_initial_view(first, with_levels(next_exact, off, 0), unit);
  ASSERT_TRUE(fine.accepted) << fine.reason;
  n = count(fine);
  EXPECT_GT(n[Exact][2], 0.9 * n[Exact][0]);
  EXPECT_LT(n[Off][1], 0.1 * n[Off][0]);
  EXPECT_LT(n[Mover][1], 0.02 * n[Mover][0]);

  // moving_factor_unmasked 3 widens the moving bound at level 0 to 3 px: the
  // points 2.5 px off stay in (still not confirmed), the movers still go.
  InitialViewCheckOptions wide;
  wide.moving_factor_unmasked = 3;
  const InitialViewCheck widened = check_initial_view(first, with_levels(next_exact, off, 0), wide);
  ASSERT_TRUE(widened.accepted) << widened.reason;
  n = count(widened);
  EXPECT_GT(n[Exact][2], 0.9 * n[Exact][0]);
  EXPECT_GT(n[Off][1], 0.9 * n[Off][0]);
  EXPECT_EQ(n[Off][2], 0);
  EXPECT_LT(n[Mover][1], 0.02 * n[Mover][0]);
  EXPECT_EQ(n[Mover][2], 0);
  wide.moving_factor_unmasked = 0.5;
  EXPECT_THROW(wide.check(), OptionError);
}

// Movers each going their own way (limbs, several people): no motion holds
// most of the matches. (A majority moving as one rigid body is, to geometry
// alone, the static world; the check cannot tell.)
TEST(InitialViewCheck, UnmaskedRejectsAViewMostlyMoving) {
  test::SyntheticScene scene(1500);
  const Frame first = scene.make_frame(0, test::pose_at(0));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> offset(-0.08, 0.08);
  for (std::size_t i : first_points(scene, 0.8)) scene.move_point(i, Eigen::Vector3d(offset(rng), offset(rng), 0));
  const Frame next = scene.make_frame(1, test::pose_at(0.02, 0, 1));
  const InitialViewCheck c = check_initial_view(first, next, {});
  EXPECT_FALSE(c.accepted);
  EXPECT_GT(static_cast<double>(c.moving) / c.matches, 0.7);
}

TEST(InitialViewCheck, RejectsWhenEitherFrameIsMostlyMasked) {
  test::SyntheticScene scene(1500);
  TwoFrames t = two_frames(scene, {}, 0);
  cv::Mat1b mask = empty_mask();
  mask.colRange(0, 384).setTo(255);  // 60 %
  t.next.set_dynamic_mask(mask);
  InitialViewCheck c = check_initial_view(t.first, t.next, {});
  EXPECT_FALSE(c.accepted);
  EXPECT_NE(c.reason.find("60 %"), std::string::npos) << c.reason;
  InitialViewCheckOptions loose;
  loose.max_masked_fraction = 0.7;
  c = check_initial_view(t.first, t.next, loose);
  EXPECT_TRUE(c.accepted) << c.reason;
}

}  // namespace
}  // namespace stillslam
