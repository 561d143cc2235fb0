// Timestamp association: TUM greedy unique matching and evo nearest neighbour.
#include <gtest/gtest.h>

#include "stillslam/core/error.h"
#include "stillslam/eval/association.h"

namespace stillslam {
namespace {

std::vector<std::pair<std::size_t, std::size_t>> as_pairs(const std::vector<IndexPair>& pairs) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (const auto& p : pairs) out.emplace_back(p.gt, p.est);
  return out;
}

using Pairs = std::vector<std::pair<std::size_t, std::size_t>>;

AssociationOptions greedy(double max_dt = 0, double offset = 0) {
  return {AssociationMethod::Greedy, max_dt, offset};
}
AssociationOptions nearest(double max_dt = 0, double offset = 0) {
  return {AssociationMethod::Nearest, max_dt, offset};
}

TEST(Association, DefaultsFollowTumAndEvo) {
  EXPECT_EQ(greedy().effective_max_dt(), 0.02);
  EXPECT_EQ(nearest().effective_max_dt(), 0.01);
  EXPECT_EQ(parse_association_method("tum"), AssociationMethod::Greedy);
  EXPECT_EQ(parse_association_method("nearest"), AssociationMethod::Nearest);
  EXPECT_THROW(parse_association_method("closest"), Error);
}

TEST(Association, GreedyTakesClosestPairsFirstAndUsesEachStampOnce) {
  const std::vector<double> gt{0.0, 0.004, 0.008, 1.0};
  const std::vector<double> est{0.003, 0.0055};
  // 0.004<->0.003 (dt 0.001) first; 0.0055 then takes the next free stamp 0.008.
  EXPECT_EQ(as_pairs(associate(gt, est, greedy())), (Pairs{{1, 0}, {2, 1}}));
  // evo: each stamp of the shorter list picks its nearest, reuse allowed.
  EXPECT_EQ(as_pairs(associate(gt, est, nearest())), (Pairs{{1, 0}, {1, 1}}));
}

TEST(Association, NearestIteratesOverTheShorterTrajectory) {
  const std::vector<double> gt{0.0, 1.0, 2.0};
  const std::vector<double> est{0.0, 0.004, 0.008, 1.0};
  EXPECT_EQ(as_pairs(associate(gt, est, nearest())), (Pairs{{0, 0}, {1, 3}}));
  EXPECT_EQ(as_pairs(associate(gt, est, greedy())), (Pairs{{0, 0}, {1, 3}}));
}

TEST(Association, DuplicateStampsKeepTheLastPoseInGreedyMode) {
  const std::vector<double> gt{0.0, 0.1, 0.2};
  const std::vector<double> est{0.005, 0.1, 0.1, 0.3};
  EXPECT_EQ(as_pairs(associate(gt, est, greedy())), (Pairs{{0, 0}, {1, 2}}));
  // Nearest: the first of equal candidates, like numpy's argmin.
  EXPECT_EQ(as_pairs(associate(gt, est, nearest())), (Pairs{{0, 0}, {1, 1}}));
}

TEST(Association, OffsetsBeyondMaxDtMatchNothingUntilCorrected) {
  const std::vector<double> gt{0.0, 1.0, 2.0};
  const std::vector<double> est{0.03, 1.03, 2.03};
  EXPECT_TRUE(associate(gt, est, greedy()).empty());
  EXPECT_TRUE(associate(gt, est, nearest()).empty());
  EXPECT_EQ(associate(gt, est, greedy(0, -0.03)).size(), 3u);
  EXPECT_EQ(associate(gt, est, nearest(0, -0.03)).size(), 3u);
  EXPECT_EQ(associate(gt, est, greedy(0.05)).size(), 3u);
}

TEST(Association, GreedyBoundIsStrictNearestBoundIsInclusive) {
  const std::vector<double> gt{0.0, 1.0};
  const std::vector<double> est{0.25, 1.5};
  EXPECT_TRUE(associate(gt, est, greedy(0.25)).empty());  // associate.py: |dt| < max_difference
  EXPECT_EQ(as_pairs(associate(gt, est, nearest(0.25))), (Pairs{{0, 0}}));  // evo: <= max_diff
}

TEST(Association, UnsortedInputGivesPairsSortedByTime) {
  const std::vector<double> gt{3.0, 1.0, 2.0, 0.0};
  const std::vector<double> est{2.001, 0.001, 3.001};
  EXPECT_EQ(as_pairs(associate(gt, est, greedy())), (Pairs{{3, 1}, {2, 0}, {0, 2}}));
  EXPECT_EQ(as_pairs(associate(gt, est, nearest())), (Pairs{{3, 1}, {2, 0}, {0, 2}}));
}

}  // namespace
}  // namespace stillslam
