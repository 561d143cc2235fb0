#include <gtest/gtest.h>

#include "common/error_text.h"
#include "stamp_pairer.h"

namespace stillslam::ros2 {
namespace {

constexpr std::int64_t kMs = 1000000;

StampedImage at(std::int64_t ms, int tag = 0) { return {ms * kMs, cv::Mat1b(1, 1, static_cast<uchar>(tag))}; }

TEST(StampPairer, PairsEqualStampsInEitherOrder) {
  StampPairer p(PairingOptions{});
  EXPECT_FALSE(p.add_first(at(0, 1)));
  const auto a = p.add_second(at(0, 2));
  ASSERT_TRUE(a);
  EXPECT_EQ(a->first.image.at<uchar>(0, 0), 1);  // first is always the left / colour image
  EXPECT_EQ(a->second.image.at<uchar>(0, 0), 2);
  EXPECT_FALSE(p.add_second(at(50, 4)));
  const auto b = p.add_first(at(50, 3));
  ASSERT_TRUE(b);
  EXPECT_EQ(b->first.image.at<uchar>(0, 0), 3);
  EXPECT_EQ(b->second.stamp_ns, 50 * kMs);
  EXPECT_EQ(p.pairs(), 2u);
  EXPECT_EQ(p.unpaired_first() + p.unpaired_second(), 0u);
}

TEST(StampPairer, PairsWithinToleranceWithTheClosestStamp) {
  PairingOptions options;
  options.tolerance_s = 0.01;
  StampPairer p(options);
  EXPECT_FALSE(p.add_first(at(100)));
  EXPECT_FALSE(p.add_first(at(104)));
  const auto pair = p.add_second(at(106));  // 6 ms from 100, 2 ms from 104
  ASSERT_TRUE(pair);
  EXPECT_EQ(pair->first.stamp_ns, 104 * kMs);
  EXPECT_EQ(p.unpaired_first(), 1u);  // 100 is older than the pair: dropped
  EXPECT_FALSE(p.add_second(at(200)));
  EXPECT_FALSE(p.add_first(at(211)));  // 11 ms apart: no pair
  EXPECT_EQ(p.unpaired_second(), 1u);  // 200 can no longer pair: the left topic is past it
  EXPECT_EQ(p.pairs(), 1u);
}

TEST(StampPairer, WaitingMessagesAreBoundedWhenOneTopicStops) {
  PairingOptions options;
  options.max_waiting = 3;
  StampPairer p(options);
  for (int i = 0; i < 10; ++i) EXPECT_FALSE(p.add_first(at(i * 50)));
  EXPECT_EQ(p.unpaired_first(), 7u);  // 10 sent, 3 still waiting
  EXPECT_TRUE(p.add_second(at(450)));  // the newest waiting one still pairs
  EXPECT_EQ(p.unpaired_first(), 9u);   // 350 and 400 are older than the pair
}

TEST(StampPairer, RejectsBadTolerance) {
  PairingOptions options;
  options.tolerance_s = 2;
  EXPECT_TRUE(test::contains(test::error_of([&] { options.check(); }), "--pair-tolerance"));
}

}  // namespace
}  // namespace stillslam::ros2
