// Keyframes per second of input (tracking/keyframe_budget.h).
#include <gtest/gtest.h>

#include "stillslam/core/option_check.h"
#include "stillslam/tracking/keyframe_budget.h"

namespace stillslam {
namespace {

// Asks on every frame of a 30 Hz input and spends whenever allowed: the
// keyframes made over `seconds`.
int keyframes_made(KeyFrameBudget& budget, double seconds) {
  int made = 0;
  for (int f = 0; f < static_cast<int>(seconds * 30); ++f) {
    const double t = f / 30.0;
    if (budget.allows(t)) {
      budget.spend(t);
      ++made;
    }
  }
  return made;
}

TEST(KeyFrameBudget, NoBudgetAllowsEveryFrame) {
  KeyFrameBudget budget({0, 2, 0});
  EXPECT_EQ(keyframes_made(budget, 2), 60);
}

TEST(KeyFrameBudget, BurstThenTheRate) {
  KeyFrameBudget budget({5, 2, 0});
  // 2 at once, then about one every 6 frames (5 per second) over the 10 s
  // (a token whole only on the 7th frame when rounding leaves it just short).
  const int made = keyframes_made(budget, 10);
  EXPECT_GE(made, 2 + 300 / 7);
  EXPECT_LE(made, 2 + 50);
  // The first two come back to back (the second leaves 1/6 of a token), the
  // third waits the remaining 5/6 / 5 = 1/6 s.
  KeyFrameBudget fresh({5, 2, 0});
  EXPECT_TRUE(fresh.allows(0));
  fresh.spend(0);
  EXPECT_TRUE(fresh.allows(1 / 30.0));
  fresh.spend(1 / 30.0);
  EXPECT_FALSE(fresh.allows(2 / 30.0));
  EXPECT_FALSE(fresh.allows(1 / 30.0 + 0.16));
  EXPECT_TRUE(fresh.allows(1 / 30.0 + 0.17));
}

TEST(KeyFrameBudget, KeyframesBeyondTheBudgetLeaveItEmptyNotInDebt) {
  KeyFrameBudget budget({2, 1, 0});
  budget.spend(0);
  // Tracking about to fail takes three more within 0.1 s.
  budget.spend(0.03);
  budget.spend(0.06);
  budget.spend(0.1);
  EXPECT_FALSE(budget.allows(0.5));
  EXPECT_TRUE(budget.allows(0.61));  // 0.5 s after the last at 2 per second
}

TEST(KeyFrameBudget, TimeGoingBackAddsNothingAndResetFillsIt) {
  KeyFrameBudget budget({1, 1, 0});
  budget.spend(10);
  EXPECT_FALSE(budget.allows(3));
  budget.spend(3);
  EXPECT_FALSE(budget.allows(3.5));
  EXPECT_TRUE(budget.allows(4));
  budget.reset();
  EXPECT_TRUE(budget.allows(0));
}

TEST(KeyFrameBudget, AMapsFirstKeyframesAreOutsideTheBudget) {
  // Every frame of the first 10 is a keyframe, then the full bucket (2), then
  // the rate.
  KeyFrameBudget exempt({5, 2, 10});
  KeyFrameBudget plain({5, 2, 0});
  for (int f = 0; f < 10; ++f) {
    EXPECT_TRUE(exempt.allows(f / 30.0)) << f;
    exempt.spend(f / 30.0);
  }
  EXPECT_TRUE(exempt.allows(10 / 30.0));  // the bucket is full: the burst
  exempt.spend(10 / 30.0);
  EXPECT_TRUE(exempt.allows(11 / 30.0));
  exempt.spend(11 / 30.0);
  EXPECT_FALSE(exempt.allows(12 / 30.0));  // and then the rate
  // Over 4 s: 2 + about 5 x 4 without the exemption; with it 10 more, less
  // the ~1.7 tokens the bucket did not gather while they came (10 frames).
  EXPECT_EQ(keyframes_made(plain, 4), 21);
  KeyFrameBudget fresh({5, 2, 10});
  EXPECT_EQ(keyframes_made(fresh, 4), 30);
  // A reset (a new map) exempts the next map's first keyframes again.
  fresh.reset();
  for (int f = 0; f < 12; ++f) {
    EXPECT_TRUE(fresh.allows(5 + f / 30.0)) << f;
    fresh.spend(5 + f / 30.0);
  }
  EXPECT_FALSE(fresh.allows(5 + 12 / 30.0));
}

TEST(KeyFrameBudget, TheStartExemptionEndsAfterItsSeconds) {
  // Up to 1000 keyframes exempt, but only within 0.18 s of the map's first:
  // frames 0-5 (frame 6 is 0.2 s after), then the full bucket (2), then the rate.
  KeyFrameBudget timed({5, 2, 1000, 0.18});
  for (int f = 0; f < 6; ++f) {
    EXPECT_TRUE(timed.allows(1 + f / 30.0)) << f;
    timed.spend(1 + f / 30.0);
  }
  for (int f = 6; f < 8; ++f) {
    EXPECT_TRUE(timed.allows(1 + f / 30.0)) << f;
    timed.spend(1 + f / 30.0);
  }
  EXPECT_FALSE(timed.allows(1 + 8 / 30.0));
  // Both limits: the count ends it first here (3 keyframes within 0.18 s).
  KeyFrameBudget both({5, 2, 3, 0.18});
  EXPECT_EQ(keyframes_made(both, 1), 3 + 2 + 4);
  KeyFrameBudget count_only({5, 2, 3});
  EXPECT_EQ(keyframes_made(count_only, 1), 3 + 2 + 4);
  // Over 4 s: 6 exempt in the first 0.18 s, then as the plain budget (21 in
  // 4 s) less the time the exemption took.
  KeyFrameBudget fresh({5, 2, 1000, 0.18});
  const int made = keyframes_made(fresh, 4);
  EXPECT_EQ(made, 6 + 2 + 18);
  // A reset (a new map) starts the clock again at the next map's first keyframe.
  fresh.reset();
  for (int f = 0; f < 6; ++f) {
    EXPECT_TRUE(fresh.allows(9 + f / 30.0)) << f;
    fresh.spend(9 + f / 30.0);
  }
  fresh.spend(9 + 6 / 30.0);
  fresh.spend(9 + 7 / 30.0);
  EXPECT_FALSE(fresh.allows(9 + 8 / 30.0));
}

TEST(KeyFrameBudget, OptionsOutOfRangeNameTheField) {
  try {
    KeyFrameBudget budget({-1, 2});
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "KeyFrameBudgetOptions.per_second");
  }
  try {
    KeyFrameBudget budget({3, 0.5});
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "KeyFrameBudgetOptions.burst");
  }
  try {
    KeyFrameBudget budget({3, 2, -1});
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "KeyFrameBudgetOptions.start_keyframes");
  }
  try {
    KeyFrameBudget budget({3, 2, 10, -1});
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "KeyFrameBudgetOptions.start_seconds");
  }
}

}  // namespace
}  // namespace stillslam
