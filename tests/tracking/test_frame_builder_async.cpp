// Frame builder with asynchronous segmentation: an ordinary frame never waits
// for a busy segmenter; it is built with the last mask, carried, and its age.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "segmentation/gated_segmenter.h"
#include "stillslam/tracking/frame_builder.h"

namespace stillslam {
namespace {

SensorFrame rgbd_input(std::size_t index) {
  cv::Mat noise(480, 640, CV_8U);
  cv::RNG rng(1);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 255);
  SensorFrame in;
  cv::GaussianBlur(noise, in.gray, cv::Size(0, 0), 1.5);
  cv::normalize(in.gray, in.gray, 0, 255, cv::NORM_MINMAX);
  cv::cvtColor(in.gray, in.color, cv::COLOR_GRAY2BGR);
  in.depth = cv::Mat(480, 640, CV_32F, cv::Scalar(2.0f));
  in.index = index;
  in.name = "test";
  return in;
}

TEST(FrameBuilderAsync, OrdinaryFramesAreBuiltWithTheCarriedMaskWhileTheSegmenterIsBusy) {
  auto gate = std::make_shared<test::Gate>();
  SegmentationStage stage(
      DynamicMaskMaker(std::make_unique<test::GatedSegmenter>(gate), {0}, 0, MaskHoldOptions{.frames = 0}), true);
  AsyncMaskOptions o;
  o.interval = 3;
  o.max_mask_age = 10;
  o.grow_px_per_frame = 2;
  AsyncMasks masks(stage, o);
  const CameraCalibration calib = pinhole_calibration(500, 500, 320, 240, 640, 480);
  const auto setup = std::make_shared<CameraSetup>(PinholeCamera(calib, 40.0), ScalePyramid(OrbOptions{}), 3.0);
  FrameBuilder builder(setup, SensorType::Rgbd, OrbOptions{}, &masks);
  ASSERT_TRUE(builder.segmentation_enabled());

  FrameBuildStats st;
  const Frame first = builder.build(rgbd_input(0), 0, &st);
  EXPECT_EQ(st.mask_age, 0);  // nothing to carry yet: its own mask (waited for, unless already there)
  EXPECT_EQ(st.segmentation_request, ScheduleReason::First);
  EXPECT_EQ(first.mask_age(), 0);
  EXPECT_NEAR(st.mask_coverage, 100.0 / (640 * 480), 1e-9);

  gate->close();
  for (std::size_t f = 1; f <= 3; ++f) builder.build(rgbd_input(f), f, &st);  // frame 3 goes to the stage
  gate->wait_blocked();
  const Frame frame = builder.build(rgbd_input(4), 4, &st);  // returns although the segmenter is blocked
  EXPECT_EQ(st.mask_age, 4);
  EXPECT_FALSE(st.mask_waited);
  EXPECT_EQ(st.segmentation_request, ScheduleReason::None);
  EXPECT_EQ(frame.mask_age(), 4);
  // Frame 0's 10x10 square at the corner, grown 2 px per frame of age: 18x18.
  EXPECT_NEAR(frame.masked_fraction(), (18.0 * 18) / (640 * 480), 1e-6);
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const cv::Point2f p = frame.keypoint(i).pt;
    EXPECT_FALSE(p.x < 18 && p.y < 18) << p;
  }
  EXPECT_GT(st.keypoints_after, 900);
  gate->release();
  EXPECT_FALSE(gate->timed_out);
}

}  // namespace
}  // namespace stillslam
