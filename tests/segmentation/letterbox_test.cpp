#include "stillslam/segmentation/letterbox.h"

#include <gtest/gtest.h>

namespace stillslam {
namespace {

TEST(Letterbox, PortraitFrameIntoLandscapeInput) {
  // bus.jpg (810x1080) into 640x480: scale 4/9, 360x480 centred with 140 px on each side.
  const Letterbox lb = Letterbox::fit({810, 1080}, {640, 480});
  EXPECT_NEAR(lb.scale, 480.0 / 1080.0, 1e-12);
  EXPECT_EQ(lb.resized, cv::Size(360, 480));
  EXPECT_EQ(lb.pad_x, 140);
  EXPECT_EQ(lb.pad_y, 0);
  const cv::Point2f p = lb.to_frame({140.0f + 180.0f, 240.0f});
  EXPECT_NEAR(p.x, 405.0, 1e-3);
  EXPECT_NEAR(p.y, 540.0, 1e-3);

  const cv::Mat in = lb.apply(cv::Mat(1080, 810, CV_8UC3, cv::Scalar(10, 20, 30)));
  ASSERT_EQ(in.size(), cv::Size(640, 480));
  EXPECT_EQ(in.at<cv::Vec3b>(240, 139), cv::Vec3b(114, 114, 114));  // padding
  EXPECT_EQ(in.at<cv::Vec3b>(240, 140), cv::Vec3b(10, 20, 30));     // image
  EXPECT_EQ(in.at<cv::Vec3b>(240, 499), cv::Vec3b(10, 20, 30));
  EXPECT_EQ(in.at<cv::Vec3b>(240, 500), cv::Vec3b(114, 114, 114));
}

TEST(Letterbox, OddPaddingRoundsLikeUltralytics) {
  // 640x480 into 512x384 fits exactly; 752x480 (EuRoC) into 512x384 leaves 57 rows: 28 on top.
  const Letterbox exact = Letterbox::fit({640, 480}, {512, 384});
  EXPECT_EQ(exact.resized, cv::Size(512, 384));
  EXPECT_EQ(exact.pad_x + exact.pad_y, 0);
  const Letterbox euroc = Letterbox::fit({752, 480}, {512, 384});
  EXPECT_EQ(euroc.resized, cv::Size(512, 327));
  EXPECT_EQ(euroc.pad_y, 28);  // round(57 / 2 - 0.1)
  EXPECT_EQ(Letterbox::fit({4000, 3}, {512, 384}).resized, cv::Size(512, 1));
}

}  // namespace
}  // namespace stillslam
