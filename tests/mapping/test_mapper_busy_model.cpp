// The modelled busy time of local mapping (mapping/mapper_busy_model.h).
#include <gtest/gtest.h>

#include "stillslam/core/option_check.h"
#include "stillslam/mapping/mapper_busy_model.h"

namespace stillslam {
namespace {

TEST(MapperBusyModel, CostGrowsWithObservationsAndIterations) {
  const MapperBusyModel model;  // 20 ms + obs * (6 + it * 0.75) us
  EXPECT_DOUBLE_EQ(model.busy_ms(0, 0), 20.0);
  EXPECT_DOUBLE_EQ(model.busy_ms(10000, 0), 80.0);
  EXPECT_DOUBLE_EQ(model.busy_ms(10000, 8), 140.0);
  MapperBusyModelOptions o;
  o.keyframe_ms = 5;
  o.observation_us = 1;
  o.observation_iteration_us = 2;
  EXPECT_DOUBLE_EQ(MapperBusyModel(o).busy_ms(1000, 3), 12.0);
}

TEST(MapperBusyModel, BusyUntilTheKeyframeIsDone) {
  MapperBusyModel model;
  EXPECT_TRUE(model.idle(0.0));
  model.add(1.0, 100.0);  // busy from 1.0 to 1.1 s
  EXPECT_FALSE(model.idle(1.0));
  EXPECT_FALSE(model.idle(1.099));
  EXPECT_TRUE(model.idle(1.1));
  EXPECT_DOUBLE_EQ(model.busy_until(), 1.1);
  EXPECT_EQ(model.queued(1.05), 0u);  // in progress, not waiting
}

TEST(MapperBusyModel, KeyframesQueueBehindTheOneInProgress) {
  MapperBusyModel model;
  model.add(1.0, 250.0);    // 1.0 .. 1.25
  model.add(1.125, 125.0);  // waits: 1.25 .. 1.375
  model.add(1.2, 62.5);     // waits: 1.375 .. 1.4375
  EXPECT_DOUBLE_EQ(model.busy_until(), 1.4375);
  EXPECT_EQ(model.queued(1.2), 2u);
  EXPECT_EQ(model.queued(1.3), 1u);
  EXPECT_EQ(model.queued(1.4), 0u);
  EXPECT_FALSE(model.idle(1.4));
  EXPECT_TRUE(model.idle(1.4375));
  // A keyframe arriving after the mapper went idle starts at once.
  model.add(2.0, 20.0);
  EXPECT_DOUBLE_EQ(model.busy_until(), 2.02);
  EXPECT_EQ(model.queued(2.0), 0u);
  model.reset();
  EXPECT_TRUE(model.idle(0.0));
  EXPECT_EQ(model.queued(0.0), 0u);
}

TEST(MapperBusyModel, RejectsNegativeCosts) {
  MapperBusyModelOptions o;
  o.observation_us = -1;
  EXPECT_THROW(o.check(), OptionError);
  EXPECT_THROW(MapperBusyModel{o}, OptionError);
}

}  // namespace
}  // namespace stillslam
