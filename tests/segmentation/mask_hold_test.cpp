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

cv::Mat1b held_union(const std::vector<cv::Mat1b>& held) {
  cv::Mat1b out(kSize, uchar{0});
  for (const cv::Mat1b& m : held) cv::bitwise_or(out, m, out);
  return out;
}

TEST(MaskHold, LostInstanceIsHeldGrowingThenDropped) {
  MaskHold hold({.frames = 3, .min_overlap = 0.3, .grow_px_per_frame = 2});
  EXPECT_TRUE(hold.update({box(40, 30, 20, 40)}, kSize, 0).empty());  // detected: nothing to add
  int previous = 20 * 40;
  for (std::size_t lost = 1; lost <= 3; ++lost) {
    const std::vector<cv::Mat1b> held = hold.update({}, kSize, lost);
    ASSERT_EQ(held.size(), 1u) << "lost frame " << lost;
    const int edge = 40 - 2 * static_cast<int>(lost);
    EXPECT_EQ(held[0](50, 50), 255);    // the person's middle
    EXPECT_EQ(held[0](50, edge), 255);  // grown by 2 px per frame
    EXPECT_EQ(held[0](50, edge - 2), 0);
    EXPECT_GT(cv::countNonZero(held[0]), previous);
    previous = cv::countNonZero(held[0]);
  }
  EXPECT_TRUE(hold.update({}, kSize, 4).empty());  // lost for more than 3 frames
  EXPECT_EQ(hold.held(), 0u);
}

TEST(MaskHold, FrameIndicesAgeAndGrowByInputFrames) {
  // Called every 3rd input frame (asynchronous segmentation): a held instance
  // grows 3 x 2 px per call and is dropped once lost for more than 7 input
  // frames, i.e. after two calls, not seven.
  MaskHold hold({.frames = 7, .min_overlap = 0.3, .grow_px_per_frame = 2});
  hold.update({box(40, 30, 20, 40)}, kSize, 0);
  const std::vector<cv::Mat1b> at3 = hold.update({}, kSize, 3);
  ASSERT_EQ(at3.size(), 1u);
  EXPECT_EQ(at3[0](50, 34), 255);  // 6 px left of the box
  EXPECT_EQ(at3[0](50, 32), 0);
  const std::vector<cv::Mat1b> at6 = hold.update({}, kSize, 6);
  ASSERT_EQ(at6.size(), 1u);
  EXPECT_EQ(at6[0](50, 28), 255);  // 12 px
  EXPECT_EQ(at6[0](50, 26), 0);
  EXPECT_TRUE(hold.update({}, kSize, 9).empty());  // lost 9 input frames > 7
  EXPECT_EQ(hold.held(), 0u);
}

TEST(MaskHold, AGapLongerThanTheHoldDropsAtOnce) {
  // --realtime dropped 12 frames: the person was last seen 12 frames ago, more
  // than the 10-frame hold, so nothing is held (a call count would hold it).
  MaskHold hold({.frames = 10, .min_overlap = 0.3, .grow_px_per_frame = 4});
  hold.update({box(40, 30, 20, 40)}, kSize, 5);
  EXPECT_TRUE(hold.update({}, kSize, 17).empty());
  EXPECT_EQ(hold.held(), 0u);
  // A gap within the hold keeps it, grown by the whole gap (6 frames x 4 px).
  hold.update({box(40, 30, 20, 40)}, kSize, 20);
  const std::vector<cv::Mat1b> held = hold.update({}, kSize, 26);
  ASSERT_EQ(held.size(), 1u);
  EXPECT_EQ(held[0](50, 40 - 24), 255);
  EXPECT_EQ(held[0](50, 40 - 27), 0);
}

TEST(MaskHold, InstanceFoundAgainIsNotHeldTwice) {
  MaskHold hold({.frames = 5, .min_overlap = 0.3, .grow_px_per_frame = 0});
  hold.update({box(40, 30, 20, 40), box(100, 30, 20, 40)}, kSize, 0);
  // The first person moved 4 px (found again); the second one is lost.
  const cv::Mat1b held = held_union(hold.update({box(44, 30, 20, 40)}, kSize, 1));
  EXPECT_EQ(cv::countNonZero(held), 20 * 40);
  EXPECT_EQ(held(50, 110), 255);
  EXPECT_EQ(held(50, 50), 0);
  // A detection covering only a sliver of a held instance does not find it.
  const cv::Mat1b still_held = held_union(hold.update({box(100, 30, 3, 40)}, kSize, 2));
  EXPECT_EQ(still_held(50, 115), 255);
}

TEST(MaskHold, ZeroFramesTurnsItOff) {
  MaskHold hold({.frames = 0});
  hold.update({box(40, 30, 20, 40)}, kSize, 0);
  EXPECT_TRUE(hold.update({}, kSize, 1).empty());
}

}  // namespace
}  // namespace stillslam
