#include <gtest/gtest.h>

#include "stillslam/place/bow_vector.h"

namespace stillslam {
namespace {

TEST(BowVector, MakeSortsAndSumsDuplicates) {
  const BowVector v = make_bow_vector({{7, 0.5}, {2, 1.0}, {7, 0.25}, {3, 2.0}});
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v.entries[0].first, 2u);
  EXPECT_EQ(v.entries[1].first, 3u);
  EXPECT_EQ(v.entries[2].first, 7u);
  EXPECT_DOUBLE_EQ(v.weight(7), 0.75);
  EXPECT_DOUBLE_EQ(v.weight(5), 0.0);
  EXPECT_DOUBLE_EQ(v.l1_norm(), 3.75);
}

TEST(BowVector, NormalizeL1) {
  BowVector v = make_bow_vector({{1, 1.0}, {4, 3.0}});
  v.normalize_l1();
  EXPECT_DOUBLE_EQ(v.weight(1), 0.25);
  EXPECT_DOUBLE_EQ(v.weight(4), 0.75);
  BowVector empty;
  empty.normalize_l1();
  EXPECT_TRUE(empty.empty());
}

TEST(BowVector, L1ScoreKnownValues) {
  const BowVector a = make_bow_vector({{1, 0.5}, {2, 0.5}});
  const BowVector b = make_bow_vector({{2, 0.5}, {3, 0.5}});
  const BowVector c = make_bow_vector({{8, 1.0}});
  EXPECT_DOUBLE_EQ(l1_score(a, a), 1.0);
  // |a - b|_1 = 0.5 + 0 + 0.5 = 1, so s = 1 - 0.5 * 1.
  EXPECT_DOUBLE_EQ(l1_score(a, b), 0.5);
  EXPECT_DOUBLE_EQ(l1_score(a, c), 0.0);
  EXPECT_DOUBLE_EQ(l1_score(a, BowVector{}), 0.0);
  // Scale invariant: vectors are compared after L1 normalization.
  const BowVector a3 = make_bow_vector({{1, 1.5}, {2, 1.5}});
  EXPECT_DOUBLE_EQ(l1_score(a3, b), 0.5);
  // Symmetric, and 1 - 0.5 * (0.1 + 0.1) for a small reweighting.
  const BowVector d = make_bow_vector({{1, 0.6}, {2, 0.4}});
  EXPECT_NEAR(l1_score(a, d), 0.9, 1e-12);
  EXPECT_NEAR(l1_score(d, a), 0.9, 1e-12);
}

TEST(FeatureVector, FeaturesOf) {
  FeatureVector f;
  f.groups = {{3, {0, 4}}, {9, {1}}, {12, {2, 3}}};
  ASSERT_NE(f.features_of(9), nullptr);
  EXPECT_EQ(*f.features_of(12), (std::vector<std::uint32_t>{2, 3}));
  EXPECT_EQ(f.features_of(4), nullptr);
  EXPECT_EQ(f.features_of(13), nullptr);
}

}  // namespace
}  // namespace stillslam
