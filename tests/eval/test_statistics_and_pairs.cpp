// Error statistics (evo definitions) and RPE pose-pair selection.
#include <gtest/gtest.h>

#include <cmath>

#include "stillslam/core/error.h"
#include "stillslam/eval/error_statistics.h"
#include "stillslam/eval/pose_pairs.h"

namespace stillslam {
namespace {

TEST(ErrorStatistics, MatchesHandComputedValues) {
  const ErrorStatistics s = compute_statistics({4.0, 1.0, 3.0, 2.0});
  EXPECT_EQ(s.count, 4u);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(7.5));
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(1.25));  // population std
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 4.0);
  EXPECT_DOUBLE_EQ(compute_statistics({5.0, 1.0, 3.0}).median, 3.0);
  EXPECT_EQ(compute_statistics({}).count, 0u);
  EXPECT_TRUE(std::isnan(compute_statistics({}).rmse));  // absent, never a perfect 0
  EXPECT_TRUE(compute_statistics({}).empty());
}

// Poses on a straight line, 0.125 m and 0.5 s apart (exact in binary).
Trajectory line(std::size_t n) {
  Trajectory t(n);
  for (std::size_t i = 0; i < n; ++i) {
    t[i].timestamp = 0.5 * static_cast<double>(i);
    t[i].T_world_cam.translation() = Eigen::Vector3d(0.125 * static_cast<double>(i), 0, 0);
  }
  return t;
}

using Pairs = std::vector<PosePair>;

TEST(PosePairs, FramesConsecutiveAndAllPairs) {
  EXPECT_EQ(select_pose_pairs(line(7), {2, DeltaUnit::Frames, false}), (Pairs{{0, 2}, {2, 4}, {4, 6}}));
  EXPECT_EQ(select_pose_pairs(line(7), {2, DeltaUnit::Frames, true}), (Pairs{{0, 2}, {1, 3}, {2, 4}, {3, 5}, {4, 6}}));
  EXPECT_EQ(select_pose_pairs(line(3), {1, DeltaUnit::Frames, false}), (Pairs{{0, 1}, {1, 2}}));
  EXPECT_TRUE(select_pose_pairs(line(3), {5, DeltaUnit::Frames, false}).empty());
  EXPECT_THROW(select_pose_pairs(line(3), {1.5, DeltaUnit::Frames, false}), Error);
  EXPECT_THROW(select_pose_pairs(line(3), {0, DeltaUnit::Frames, false}), Error);
}

TEST(PosePairs, MetresFollowEvoPathFilter) {
  // evo starts at the first pose whose path reaches delta: ids 4, 8, 12.
  EXPECT_EQ(select_pose_pairs(line(13), {0.5, DeltaUnit::Meters, false}), (Pairs{{4, 8}, {8, 12}}));
  const Pairs all = select_pose_pairs(line(8), {0.5, DeltaUnit::Meters, true});
  EXPECT_EQ(all, (Pairs{{0, 4}, {1, 5}, {2, 6}, {3, 7}}));
}

TEST(PosePairs, SecondsStepFromTheFirstPose) {
  // Stamps 0, 0.5, ..., 4 s: ids 0, 3 (1.5 s), 6 (3 s); 4.5 s is never reached.
  EXPECT_EQ(select_pose_pairs(line(9), {1.5, DeltaUnit::Seconds, false}), (Pairs{{0, 3}, {3, 6}}));
  EXPECT_EQ(select_pose_pairs(line(6), {1.0, DeltaUnit::Seconds, true}), (Pairs{{0, 2}, {1, 3}, {2, 4}, {3, 5}}));
}

}  // namespace
}  // namespace stillslam
