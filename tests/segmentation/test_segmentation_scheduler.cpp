#include "stillslam/segmentation/segmentation_scheduler.h"

#include <gtest/gtest.h>

#include "stillslam/core/option_check.h"

namespace stillslam {
namespace {

TEST(SegmentationScheduler, FirstFrameThenEveryIntervalFrames) {
  SegmentationScheduler s(3);
  std::vector<ScheduleReason> got;
  for (std::size_t f = 0; f < 8; ++f) got.push_back(s.decide(f, false));
  const std::vector<ScheduleReason> want{ScheduleReason::First,    ScheduleReason::None, ScheduleReason::None,
                                         ScheduleReason::Interval, ScheduleReason::None, ScheduleReason::None,
                                         ScheduleReason::Interval, ScheduleReason::None};
  EXPECT_EQ(got, want);
}

TEST(SegmentationScheduler, IntervalCountsFromTheLastRequestAcrossDroppedFrames) {
  SegmentationScheduler s(4);
  EXPECT_EQ(s.decide(10, false), ScheduleReason::First);
  EXPECT_EQ(s.decide(13, false), ScheduleReason::None);
  EXPECT_EQ(s.decide(15, false), ScheduleReason::Interval);  // 14 was dropped (realtime)
  EXPECT_EQ(s.decide(18, false), ScheduleReason::None);
  EXPECT_EQ(s.decide(19, true), ScheduleReason::Interval);  // a busy stage still gets interval frames
}

TEST(SegmentationScheduler, UrgentTakesTheNextSlotOnlyWhenTheStageIsIdle) {
  SegmentationScheduler s(10);
  EXPECT_EQ(s.decide(0, false), ScheduleReason::First);
  s.request_urgent();
  EXPECT_EQ(s.decide(1, true), ScheduleReason::None);  // busy: stays urgent
  EXPECT_TRUE(s.urgent());
  EXPECT_EQ(s.decide(2, false), ScheduleReason::Urgent);
  EXPECT_FALSE(s.urgent());
  EXPECT_EQ(s.decide(3, false), ScheduleReason::None);
  EXPECT_EQ(s.decide(12, false), ScheduleReason::Interval);  // ten frames after the urgent one
}

TEST(SegmentationScheduler, AWaitingRequestRestartsTheIntervalAndClearsUrgency) {
  SegmentationScheduler s(3);
  EXPECT_EQ(s.decide(0, false), ScheduleReason::First);
  s.request_urgent();
  s.record_request(1);
  EXPECT_FALSE(s.urgent());
  EXPECT_EQ(s.decide(3, false), ScheduleReason::None);
  EXPECT_EQ(s.decide(4, false), ScheduleReason::Interval);
}

TEST(SegmentationScheduler, IntervalBelowOneIsRejectedByName) {
  try {
    SegmentationScheduler s(0);
    FAIL() << "no error";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "SegmentationOptions.interval");
  }
}

}  // namespace
}  // namespace stillslam
