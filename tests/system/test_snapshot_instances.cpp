// The segmenter's detections as the frame snapshot shows them.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "stillslam/system/snapshot_instances.h"

namespace stillslam {
namespace {

Detection disc_person() {
  Detection d;
  d.class_id = 0;
  d.class_name = "person";
  d.score = 0.8f;
  d.box = cv::Rect2f(99.5f, 79.5f, 41.f, 41.f);
  d.mask = cv::Mat1b::zeros(240, 320);
  cv::circle(d.mask, {120, 100}, 20, 255, cv::FILLED);
  cv::circle(d.mask, {10, 10}, 3, 255, cv::FILLED);  // a speck outside the box: not the outline
  return d;
}

TEST(SnapshotInstances, OutlineClassScoreAndDynamicFlag) {
  Detection chair;
  chair.class_id = 56;
  chair.class_name = "chair";
  chair.score = 0.5f;
  chair.box = cv::Rect2f(10, 20, 30, 40);  // no mask: only the box
  const auto out = snapshot_instances({disc_person(), chair}, {0});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].class_name, "person");
  EXPECT_EQ(out[0].class_id, 0);
  EXPECT_FLOAT_EQ(out[0].score, 0.8f);
  EXPECT_TRUE(out[0].dynamic);
  EXPECT_EQ(out[0].box, cv::Rect(99, 79, 42, 42));
  ASSERT_GE(out[0].outline.size(), 8u);
  EXPECT_NEAR(cv::contourArea(out[0].outline), CV_PI * 20 * 20, 0.1 * CV_PI * 20 * 20);
  for (const cv::Point& p : out[0].outline) EXPECT_NEAR(cv::norm(cv::Point2d(p) - cv::Point2d(120, 100)), 20, 1.5);
  EXPECT_FALSE(out[1].dynamic);
  EXPECT_EQ(out[1].box, cv::Rect(10, 20, 30, 40));
  EXPECT_TRUE(out[1].outline.empty());
}

}  // namespace
}  // namespace stillslam
