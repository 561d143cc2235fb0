// Keyframe decision while local mapping is busy (tracking/keyframe_admission.h).
#include <gtest/gtest.h>

#include "stillslam/tracking/keyframe_admission.h"

namespace stillslam {
namespace {

TEST(KeyFrameAdmission, IdleMapperTakesTheKeyframeWithoutInterrupting) {
  const KeyFrameAdmission a = admit_keyframe(true, false, false, 0, false);
  EXPECT_TRUE(a.insert);
  EXPECT_FALSE(a.interrupt_bundle_adjustment);
  EXPECT_FALSE(admit_keyframe(true, true, false, 2, true).interrupt_bundle_adjustment);
}

TEST(KeyFrameAdmission, BusyMapperMakesAnOrdinaryKeyframeWait) {
  const KeyFrameAdmission a = admit_keyframe(false, false, false, 0, true);
  EXPECT_FALSE(a.insert);
  EXPECT_FALSE(a.interrupt_bundle_adjustment);
}

TEST(KeyFrameAdmission, TooFewClosePointsQueueOneKeyframeBehindTheBundleAdjustment) {
  EXPECT_TRUE(admit_keyframe(false, false, true, 0, false).insert);
  EXPECT_FALSE(admit_keyframe(false, false, true, 0, true).interrupt_bundle_adjustment);
  EXPECT_FALSE(admit_keyframe(false, false, true, 1, true).insert);
  EXPECT_FALSE(admit_keyframe(false, false, true, 1, true).interrupt_bundle_adjustment);
}

TEST(KeyFrameAdmission, WeakTrackingQueuesUpToThree) {
  EXPECT_TRUE(admit_keyframe(false, true, false, 0, false).insert);
  EXPECT_TRUE(admit_keyframe(false, true, false, 2, false).insert);
  EXPECT_TRUE(admit_keyframe(false, true, false, 2, true).insert);
  EXPECT_FALSE(admit_keyframe(false, true, true, 3, true).insert);
}

TEST(KeyFrameAdmission, OnlyAnUrgentWeakFrameWithABacklogInterrupts) {
  // Urgent, a keyframe already waiting: the BA stops.
  EXPECT_TRUE(admit_keyframe(false, true, false, 1, true).interrupt_bundle_adjustment);
  EXPECT_TRUE(admit_keyframe(false, true, false, 2, true).interrupt_bundle_adjustment);
  // Not urgent (enough inliers): it queues behind the BA, even with a backlog.
  EXPECT_FALSE(admit_keyframe(false, true, false, 1, false).interrupt_bundle_adjustment);
  EXPECT_FALSE(admit_keyframe(false, true, false, 2, false).interrupt_bundle_adjustment);
  // Urgent without a backlog: the mapper gets the keyframe after this BA.
  EXPECT_FALSE(admit_keyframe(false, true, false, 0, true).interrupt_bundle_adjustment);
}

}  // namespace
}  // namespace stillslam
