// MaskHold: a dynamic instance the segmenter loses stays masked for a few
// frames, growing; one found again or lost for too long is dropped.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "stillslam/segmentation/mask_hold.h"

namespace stillslam {
namespace {

const cv::Size kSize(160, 120);

cv::Mat1b box(int x, int y, int w, int h) {
  cv::Mat1b m(kSize, uchar{0});
  m(cv::Rect(x, y, w, h)).setTo(255);
  return m;
}

TEST(MaskHold, LostInstanceIsHeldGrowingThenDropped) {
  MaskHold hold({.frames = 3, .min_overlap = 0.3, .grow_px_per_frame = 2});
  EXPECT_TRUE(hold.update({box(40, 30, 20, 40)}, kSize).empty());  // detected: nothing to add
  int previous = 20 * 40;
  for (int lost = 1; lost <= 3; ++lost) {
    const cv::Mat1b held = hold.update({}, kSize);
    ASSERT_FALSE(held.empty()) << "lost frame " << lost;
    EXPECT_EQ(held(50, 50), 255);            // the person's middle
    EXPECT_EQ(held(50, 40 - 2 * lost), 255);  // grown by 2 px per frame
    EXPECT_EQ(held(50, 40 - 2 * lost - 2), 0);
    EXPECT_GT(cv::countNonZero(held), previous);
    previous = cv::countNonZero(held);
  }
  EXPECT_TRUE(hold.update({}, kSize).empty());  // lost for more than 3 frames
  EXPECT_EQ(hold.held(), 0u);
}

TEST(MaskHold, InstanceFoundAgainIsNotHeldTwice) {
  MaskHold hold({.frames = 5, .min_overlap = 0.3, .grow_px_per_frame = 0});
  hold.update({box(40, 30, 20, 40), box(100, 30, 20, 40)}, kSize);
  // The first person moved 4 px (found again); the second one is lost.
  const cv::Mat1b held = hold.update({box(44, 30, 20, 40)}, kSize);
  ASSERT_FALSE(held.empty());
  EXPECT_EQ(cv::countNonZero(held), 20 * 40);
  EXPECT_EQ(held(50, 110), 255);
  EXPECT_EQ(held(50, 50), 0);
  // A detection covering only a sliver of a held instance does not find it.
  const cv::Mat1b still_held = hold.update({box(100, 30, 3, 40)}, kSize);
  ASSERT_FALSE(still_held.empty());
  EXPECT_EQ(still_held(50, 115), 255);
}

TEST(MaskHold, ZeroFramesTurnsItOff) {
  MaskHold hold({.frames = 0});
  hold.update({box(40, 30, 20, 40)}, kSize);
  EXPECT_TRUE(hold.update({}, kSize).empty());
}

}  // namespace
}  // namespace stillslam
