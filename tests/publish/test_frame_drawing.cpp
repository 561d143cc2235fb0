// draw_frame: each kind of mark in its own colour at its place, on a copy.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "stillslam/core/option_check.h"
#include "stillslam/publish/frame_drawing.h"

namespace stillslam {
namespace {

cv::Vec3b bgr(const cv::Scalar& s) {
  return {static_cast<uchar>(s[0]), static_cast<uchar>(s[1]), static_cast<uchar>(s[2])};
}

int count_color(const cv::Mat& image, const cv::Vec3b& color) {
  int n = 0;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) n += image.at<cv::Vec3b>(y, x) == color ? 1 : 0;
  }
  return n;
}

TEST(FrameDrawing, EachMarkInItsColourOnACopy) {
  FrameSnapshot frame;
  frame.image = cv::Mat(120, 160, CV_8UC1, cv::Scalar(128));  // gray input: drawn in colour
  frame.keypoints = {{20, 60}, {60, 60}};
  frame.tracked = {true, false};
  frame.removed_keypoints = {{120, 60}};
  FrameSnapshot::Instance person;
  person.class_name = "person";
  person.score = 0.9f;
  person.box = cv::Rect(100, 40, 40, 40);
  person.outline = {{100, 40}, {139, 40}, {139, 79}, {100, 79}};
  person.dynamic = true;
  frame.instances = {person};
  FrameDrawingOptions options;
  options.text = false;
  const cv::Mat drawn = draw_frame(frame, options);
  ASSERT_EQ(drawn.type(), CV_8UC3);
  ASSERT_EQ(drawn.size(), frame.image.size());
  EXPECT_EQ(frame.image.at<uchar>(60, 23), 128) << "the input image is not drawn on";
  // A circle of radius 3 passes through (x+3, y); a cross covers its centre.
  EXPECT_EQ(drawn.at<cv::Vec3b>(60, 23), bgr(options.tracked));
  EXPECT_EQ(drawn.at<cv::Vec3b>(60, 63), bgr(options.untracked));
  EXPECT_EQ(drawn.at<cv::Vec3b>(60, 120), bgr(options.removed));
  EXPECT_EQ(drawn.at<cv::Vec3b>(79, 110), bgr(options.mask));  // the outline's bottom edge
  EXPECT_EQ(count_color(drawn, bgr(options.static_instance)), 0);
  EXPECT_GT(count_color(drawn, bgr(options.removed)), 4);
}

TEST(FrameDrawing, NoImageDrawsNothingAndOptionsAreChecked) {
  EXPECT_TRUE(draw_frame(FrameSnapshot{}).empty());
  FrameDrawingOptions options;
  options.feature_radius = 0;
  EXPECT_THROW(options.check(), OptionError);
}

}  // namespace
}  // namespace stillslam
