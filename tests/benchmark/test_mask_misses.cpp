// bench/oracle_segmenter.h's choice of missed frames (bench_slam
// --mask-miss-rate, bench_mask_misses): exact counts, bursts, a fixed seed.
#include <gtest/gtest.h>

#include "../bench/oracle_segmenter.h"

namespace stillslam {
namespace {

std::size_t count(const std::vector<bool>& v) { return static_cast<std::size_t>(std::count(v.begin(), v.end(), true)); }

TEST(MaskMisses, RandomFramesHitTheRateExactlyAndRepeatWithTheSeed) {
  oracle::MaskMissOptions o;
  o.rate = 0.3;
  const std::vector<bool> a = oracle::choose_missed_frames(240, o);
  EXPECT_EQ(count(a), 72u);
  EXPECT_EQ(a, oracle::choose_missed_frames(240, o));
  o.seed = 2;
  const std::vector<bool> b = oracle::choose_missed_frames(240, o);
  EXPECT_EQ(count(b), 72u);
  EXPECT_NE(a, b);
  o.rate = 0;
  EXPECT_EQ(count(oracle::choose_missed_frames(240, o)), 0u);
  o.rate = 1;
  EXPECT_EQ(count(oracle::choose_missed_frames(240, o)), 240u);
}

TEST(MaskMisses, BurstsAreWholeSecondsAtTheirStart) {
  oracle::MaskMissOptions o;
  o.rate = 0.5;
  o.burst_seconds = 1;
  o.fps = 30;
  const std::vector<bool> m = oracle::choose_missed_frames(300, o);
  EXPECT_EQ(count(m), 150u);  // 5 of the 10 one-second blocks
  for (std::size_t b = 0; b < 10; ++b) {
    const bool first = m[b * 30];
    for (std::size_t f = b * 30; f < (b + 1) * 30; ++f) ASSERT_EQ(m[f], first) << "frame " << f;
  }
}

}  // namespace
}  // namespace stillslam
