#include <gtest/gtest.h>

#include "common/error_text.h"
#include "frame_assembler.h"
#include "stillslam/io/dataset.h"
#include "stillslam/io/image_io.h"

namespace stillslam::ros2 {
namespace {

Settings rgbd_settings() {
  Settings s;
  s.file = "rgbd.yaml";
  s.rgbd = true;
  s.camera = pinhole_calibration(500, 500, 3, 2, 6, 4);
  return s;
}

TEST(FrameAssembler, RgbdDepthIn16BitMillimetresBecomesMetres) {
  const FrameAssembler assembler(rgbd_settings(), false);
  EXPECT_EQ(assembler.sensor(), SensorType::Rgbd);
  ImagePair pair{{1500000000LL, cv::Mat3b(4, 6, cv::Vec3b(0, 0, 255))}, {1500000000LL, cv::Mat1w(4, 6, 1250)}};
  const SensorFrame f = assembler.assemble(pair, 7, "rgb", "depth");
  EXPECT_EQ(f.index, 7u);
  EXPECT_DOUBLE_EQ(f.timestamp, 1.5);
  ASSERT_EQ(f.depth.type(), CV_32FC1);
  EXPECT_FLOAT_EQ(f.depth.at<float>(3, 5), 1.25f);
  EXPECT_EQ(f.gray.type(), CV_8UC1);
  EXPECT_EQ(f.color.at<cv::Vec3b>(0, 0), cv::Vec3b(0, 0, 255));
}

TEST(FrameAssembler, ImagesOfAnotherSizeThanTheSettingsAreAnError) {
  const FrameAssembler assembler(rgbd_settings(), false);
  ImagePair pair{{0, cv::Mat3b(8, 12)}, {0, cv::Mat1f(8, 12)}};
  const std::string e = test::error_of([&] { assembler.assemble(pair, 0, "rt/rgb", "rt/depth"); });
  EXPECT_TRUE(test::contains(e, "rt/rgb: image is 12x8 but rgbd.yaml says Camera.width/height 6x4")) << e;
}

// Raw stereo images from a camera driver are rectified exactly as the EuRoC
// reader rectifies its files: the System sees the same pixels either way.
TEST(FrameAssembler, RawStereoIsRectifiedLikeTheDatasetReader) {
  const std::filesystem::path clip = std::filesystem::path(STILLSLAM_SHARED_DIR) / "data" / "euroc_V1_01_micro";
  if (!std::filesystem::exists(clip)) GTEST_SKIP() << clip << " is absent (../shared is not on this machine)";
  const Settings settings = load_settings(std::string(STILLSLAM_SOURCE_DIR) + "/config/euroc.yaml");
  const FrameAssembler assembler(settings, false);
  const auto dataset = open_dataset(clip, settings);
  const SensorFrame expected = dataset->load(0);
  const std::string name = "1403715273262142976.png";
  ImagePair pair{{1403715273262142976LL, read_gray_or_color_image(clip / "mav0" / "cam0" / "data" / name)},
                 {1403715273262142976LL, read_gray_or_color_image(clip / "mav0" / "cam1" / "data" / name)}};
  const SensorFrame f = assembler.assemble(pair, 0, "left", "right");
  EXPECT_EQ(cv::norm(f.gray, expected.gray, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(f.right, expected.right, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(f.color, expected.color, cv::NORM_INF), 0.0);
  ASSERT_TRUE(assembler.rectified_stereo());
  EXPECT_DOUBLE_EQ(assembler.rectified_stereo()->left.fx, dataset->rectified_stereo()->left.fx);
  EXPECT_DOUBLE_EQ(assembler.rectified_stereo()->baseline, dataset->rectified_stereo()->baseline);
  // --rectified-input: the images go through untouched.
  const FrameAssembler as_is(settings, true);
  EXPECT_EQ(cv::norm(as_is.assemble(pair, 0, "left", "right").gray, pair.first.image, cv::NORM_INF), 0.0);
}

TEST(FrameAssembler, SettingsWithoutStereoOrDepthAreAnError) {
  Settings s;
  s.file = "mono.yaml";
  EXPECT_TRUE(test::contains(test::error_of([&] { sensor_of(s); }), "mono.yaml: describes neither a stereo pair"));
}

}  // namespace
}  // namespace stillslam::ros2
