#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "io/dataset_fixtures.h"
#include "io/temp_dir.h"
#include "stillslam/core/error.h"
#include "stillslam/io/dataset.h"

namespace stillslam {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

TEST(KittiDataset, ReadsCalibTimesAndImages) {
  TempDir dir;
  const fs::path seq = test::write_kitti_fixture(dir.path(), 3, true);
  const auto d = open_dataset(seq, CameraSettings{});
  EXPECT_EQ(d->kind(), "kitti");
  EXPECT_EQ(d->sensor(), SensorType::Stereo);
  ASSERT_EQ(d->size(), 3u);
  EXPECT_DOUBLE_EQ(d->timestamp(2), 0.2072);
  const auto s = d->rectified_stereo();
  ASSERT_TRUE(s.has_value());
  EXPECT_TRUE(s->rectified);
  EXPECT_DOUBLE_EQ(s->left.fx, 718.856);
  EXPECT_DOUBLE_EQ(s->left.cy, 185.2157);
  EXPECT_NEAR(s->baseline, 386.1448 / 718.856, 1e-12);
  EXPECT_EQ(s->left.width, 96);
  EXPECT_EQ(s->left.height, 32);

  const SensorFrame f = d->load(1);
  EXPECT_EQ(f.name, "000001.png");
  ASSERT_EQ(f.gray.type(), CV_8UC1);
  ASSERT_EQ(f.color.type(), CV_8UC3);
  const cv::Mat expected_left = test::textured_image(96, 32, 1, 2);
  const cv::Mat expected_right = test::textured_image(96, 32, 1, 3);
  EXPECT_EQ(cv::norm(f.gray, expected_left, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(f.right, expected_right, cv::NORM_INF), 0.0);
  EXPECT_EQ(f.color.at<cv::Vec3b>(5, 7)[2], f.gray.at<std::uint8_t>(5, 7));
}

TEST(KittiDataset, FallsBackToSettingsWithoutCalib) {
  TempDir dir;
  const fs::path seq = test::write_kitti_fixture(dir.path(), 2, false);
  const CameraSettings kitti = load_camera_settings(fs::path(STILLSLAM_SOURCE_DIR) / "config" / "kitti_04-12.yaml");
  const auto s = open_dataset(seq, kitti)->rectified_stereo();
  ASSERT_TRUE(s.has_value());
  EXPECT_DOUBLE_EQ(s->left.fx, 707.0912);
  EXPECT_NEAR(s->baseline, 379.8145 / 707.0912, 1e-12);
  EXPECT_EQ(s->left.width, 96);  // the images win over Camera.width
  try {
    open_dataset(seq, CameraSettings{});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("calib.txt: missing, and the settings give no baseline"),
              std::string::npos)
        << e.what();
  }
}

TEST(KittiDataset, MissingImageAndSkip) {
  TempDir dir;
  const fs::path seq = test::write_kitti_fixture(dir.path(), 3, true);
  fs::remove(seq / "image_1" / "000002.png");
  const auto d = open_dataset(seq, CameraSettings{});
  try {
    d->load(2);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("image_1/000002.png: image file is missing"), std::string::npos)
        << e.what();
  }
  DatasetOptions options;
  options.skip_bad_frames = true;
  const auto s = open_dataset(seq, CameraSettings{}, options);
  EXPECT_TRUE(s->load(1).valid);
  const SensorFrame bad = s->load(2);
  EXPECT_FALSE(bad.valid);
  EXPECT_EQ(bad.name, "000002.png");
  EXPECT_EQ(s->skipped_frames(), 1u);
}

}  // namespace
}  // namespace stillslam
