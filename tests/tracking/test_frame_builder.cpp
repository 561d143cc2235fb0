// Frame builder: ORB + dynamic filter before depth/stereo association.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "stillslam/core/error.h"
#include "stillslam/tracking/frame_builder.h"

namespace stillslam {
namespace {

// Reports one "person" whose mask is the left half of the image.
class LeftHalfPerson final : public Segmenter {
 public:
  std::vector<Detection> segment(const cv::Mat& bgr) override {
    Detection d;
    d.class_id = 0;
    d.class_name = "person";
    d.score = 0.9f;
    d.box = cv::Rect2f(0, 0, static_cast<float>(bgr.cols / 2), static_cast<float>(bgr.rows));
    d.mask = cv::Mat1b::zeros(bgr.rows, bgr.cols);
    d.mask(cv::Rect(0, 0, bgr.cols / 2, bgr.rows)).setTo(255);
    return {d};
  }
};

cv::Mat textured_image(int seed) {
  cv::Mat noise(480, 640, CV_8U);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 255);
  cv::Mat img;
  cv::GaussianBlur(noise, img, cv::Size(0, 0), 1.5);
  cv::normalize(img, img, 0, 255, cv::NORM_MINMAX);
  return img;
}

std::shared_ptr<CameraSetup> make_setup(double bf) {
  const CameraCalibration calib = pinhole_calibration(500, 500, 320, 240, 640, 480);
  return std::make_shared<CameraSetup>(PinholeCamera(calib, bf), ScalePyramid(OrbOptions{}), 3.0);
}

SensorFrame rgbd_input() {
  SensorFrame in;
  in.gray = textured_image(1);
  cv::cvtColor(in.gray, in.color, cv::COLOR_GRAY2BGR);
  in.depth = cv::Mat(480, 640, CV_32F, cv::Scalar(2.0f));
  in.name = "test";
  return in;
}

TEST(FrameBuilder, RgbdWithoutSegmentationKeepsEveryKeypointWithDepth) {
  const auto setup = make_setup(40.0);
  FrameBuilder builder(setup, SensorType::Rgbd, OrbOptions{}, nullptr);
  FrameBuildStats stats;
  const Frame frame = builder.build(rgbd_input(), 0, &stats);
  EXPECT_GT(stats.keypoints_before, 900);
  EXPECT_EQ(stats.keypoints_after, stats.keypoints_before);
  EXPECT_EQ(static_cast<int>(frame.size()), stats.keypoints_after);
  EXPECT_EQ(stats.keypoints_with_depth, stats.keypoints_after);
  EXPECT_EQ(stats.detections, 0);
  for (std::size_t i = 0; i < frame.size(); ++i) {
    EXPECT_FLOAT_EQ(frame.depth(i), 2.0f);
    EXPECT_NEAR(frame.u_right(i), frame.keypoint(i).pt.x - 20.0f, 1e-3);
  }
}

TEST(FrameBuilder, DynamicKeypointsAreDroppedBeforeAssociation) {
  // The left half is a "person": no keypoint is kept on it, and the feature
  // budget goes to the right half instead (extraction outside the mask).
  const auto setup = make_setup(40.0);
  SegmentationWorker worker(std::make_unique<LeftHalfPerson>(), {0}, 0);
  FrameBuilder plain(setup, SensorType::Rgbd, OrbOptions{}, nullptr);
  FrameBuilder masked(setup, SensorType::Rgbd, OrbOptions{}, &worker);
  FrameBuildStats s_plain, s_masked;
  const Frame all = plain.build(rgbd_input(), 0, &s_plain);
  const Frame kept = masked.build(rgbd_input(), 0, &s_masked);
  EXPECT_EQ(s_masked.detections, 1);
  EXPECT_NEAR(s_masked.mask_coverage, 0.5, 1e-9);
  EXPECT_NEAR(kept.masked_fraction(), 0.5, 1e-6);  // what tracking's initialization looks at
  EXPECT_EQ(all.masked_fraction(), 0.f);
  int right_half = 0;
  for (std::size_t i = 0; i < all.size(); ++i) right_half += std::lround(all.keypoints_raw()[i].pt.x) >= 320 ? 1 : 0;
  EXPECT_LT(right_half, 0.6 * s_plain.keypoints_after);
  EXPECT_GT(s_masked.keypoints_after, 0.9 * s_plain.keypoints_after);
  EXPECT_EQ(s_masked.keypoints_after, s_masked.keypoints_before);
  EXPECT_EQ(static_cast<int>(kept.size()), s_masked.keypoints_after);
  for (std::size_t i = 0; i < kept.size(); ++i) EXPECT_GE(std::lround(kept.keypoint(i).pt.x), 320);
  EXPECT_EQ(s_masked.keypoints_with_depth, s_masked.keypoints_after);
}

TEST(FrameBuilder, RemovedFeaturesAreReportedInsideTheMask) {
  // The viewer shows what the mask removed: corners on the "person",
  // thinned to about the share of the budget the mask covers.
  const auto setup = make_setup(40.0);
  SegmentationWorker worker(std::make_unique<LeftHalfPerson>(), {0}, 0);
  FrameBuilder masked(setup, SensorType::Rgbd, OrbOptions{}, &worker);
  FrameBuildStats stats;
  FrameDynamics dynamics;
  masked.build(rgbd_input(), 0, &stats, &dynamics);
  ASSERT_EQ(dynamics.detections.size(), 1u);
  EXPECT_EQ(dynamics.detections[0].class_name, "person");
  const int removed = static_cast<int>(dynamics.removed_keypoints.size());
  EXPECT_GT(removed, 0.3 * OrbOptions{}.n_features);
  EXPECT_LE(removed, 0.55 * OrbOptions{}.n_features);
  for (const cv::Point2f& p : dynamics.removed_keypoints) EXPECT_LT(p.x, 321.f);
}

TEST(FrameBuilder, StereoDepthFromRectifiedPair) {
  const double bf = 50.0;  // 0.1 m baseline at fx 500
  const auto setup = make_setup(bf);
  FrameBuilder builder(setup, SensorType::Stereo, OrbOptions{}, nullptr);
  SensorFrame in;
  in.gray = textured_image(2);
  // Right image: the scene 10 px to the left (disparity 10 -> depth 5 m).
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, -10, 0, 1, 0);
  cv::warpAffine(in.gray, in.right, shift, in.gray.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  FrameBuildStats stats;
  const Frame frame = builder.build(in, 0, &stats);
  int close = 0;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (frame.depth(i) > 0) close += std::abs(frame.depth(i) - 5.0f) < 0.1f ? 1 : 0;
  }
  EXPECT_GT(stats.keypoints_with_depth, stats.keypoints_after / 2);
  EXPECT_GT(close, 0.95 * stats.keypoints_with_depth);
}

TEST(FrameBuilder, MissingImagesAreReported) {
  const auto setup = make_setup(40.0);
  FrameBuilder builder(setup, SensorType::Rgbd, OrbOptions{}, nullptr);
  SensorFrame in = rgbd_input();
  in.depth.release();
  EXPECT_THROW(builder.build(in, 0, nullptr), Error);
}

}  // namespace
}  // namespace stillslam
