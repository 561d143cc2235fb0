// Keyframe decision while local mapping is busy (tracking/keyframe_admission.h).
#include <gtest/gtest.h>

#include "stillslam/tracking/keyframe_admission.h"

namespace stillslam {
namespace {

TEST(KeyFrameAdmission, IdleMapperTakesTheKeyframeWithoutInterrupting) {
  const KeyFrameAdmission a = admit_keyframe(true, false, false, 0);
  EXPECT_TRUE(a.insert);
  EXPECT_FALSE(a.interrupt_bundle_adjustment);
}

TEST(KeyFrameAdmission, BusyMapperMakesAnOrdinaryKeyframeWait) {
  const KeyFrameAdmission a = admit_keyframe(false, false, false, 0);
  EXPECT_FALSE(a.insert);
  EXPECT_FALSE(a.interrupt_bundle_adjustment);
}

TEST(KeyFrameAdmission, TooFewClosePointsQueueOneKeyframeBehindTheBundleAdjustment) {
  EXPECT_TRUE(admit_keyframe(false, false, true, 0).insert);
  EXPECT_FALSE(admit_keyframe(false, false, true, 0).interrupt_bundle_adjustment);
  EXPECT_FALSE(admit_keyframe(false, false, true, 1).insert);
}

TEST(KeyFrameAdmission, WeakTrackingQueuesUpToThreeAndInterruptsOnlyABacklog) {
  EXPECT_TRUE(admit_keyframe(false, true, false, 0).insert);
  EXPECT_FALSE(admit_keyframe(false, true, false, 0).interrupt_bundle_adjustment);
  EXPECT_TRUE(admit_keyframe(false, true, false, 2).insert);
  EXPECT_TRUE(admit_keyframe(false, true, false, 2).interrupt_bundle_adjustment);
  EXPECT_FALSE(admit_keyframe(false, true, true, 3).insert);
}

}  // namespace
}  // namespace stillslam
