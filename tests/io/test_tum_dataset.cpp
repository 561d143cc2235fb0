#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <thread>

#include <opencv2/imgcodecs.hpp>

#include "io/dataset_fixtures.h"
#include "io/temp_dir.h"
#include "stillslam/core/error.h"
#include "stillslam/io/dataset.h"
#include "stillslam/io/tum_dataset.h"
#include "common/error_text.h"

namespace stillslam {
namespace {

using test::contains;
using test::error_of;

using test::TempDir;
namespace fs = std::filesystem;

CameraSettings tum_settings() {
  CameraSettings s;
  s.camera.fx = s.camera.fy = 525;
  s.camera.cx = 32;
  s.camera.cy = 24;
  s.depth_map_factor = 5000;
  return s;
}

TEST(TumDataset, AssociatesListsAndLoadsFrames) {
  TempDir dir;
  const fs::path seq = test::write_tum_fixture(dir.path(), 5);
  const auto dataset = open_dataset(seq, tum_settings());
  EXPECT_EQ(dataset->kind(), "tum");
  EXPECT_EQ(dataset->sensor(), SensorType::Rgbd);
  ASSERT_EQ(dataset->size(), 5u);  // the sixth rgb frame has no depth partner
  EXPECT_DOUBLE_EQ(dataset->timestamp(0), 100.0);
  EXPECT_NEAR(dataset->timestamp(3), 100.1, 1e-6);
  EXPECT_FALSE(dataset->rectified_stereo().has_value());

  const SensorFrame f = dataset->load(3);
  EXPECT_TRUE(f.valid);
  EXPECT_EQ(f.index, 3u);
  EXPECT_NEAR(f.timestamp, 100.1, 1e-6);
  EXPECT_EQ(f.name, "rgb/100.100000.png");
  ASSERT_EQ(f.color.type(), CV_8UC3);
  ASSERT_EQ(f.gray.type(), CV_8UC1);
  ASSERT_EQ(f.depth.type(), CV_32FC1);
  EXPECT_TRUE(f.right.empty());
  EXPECT_EQ(f.color.size(), cv::Size(64, 48));
  // Colour stays in file/imread order (BGR) whatever Camera.RGB says.
  EXPECT_EQ(f.color.at<cv::Vec3b>(0, 0), cv::Vec3b(10, 20, 30));
  // Gray is the BGR->gray conversion: 0.114*10 + 0.587*20 + 0.299*30 = 21.9.
  EXPECT_EQ(f.gray.at<std::uint8_t>(0, 0), 22);
  EXPECT_FLOAT_EQ(f.depth.at<float>(10, 10), (5000.0f + 300.0f) / 5000.0f);
  EXPECT_FLOAT_EQ(f.depth.at<float>(0, 0), 0.0f);  // 0 stays invalid

  // DepthMapFactor is applied as given.
  CameraSettings s = tum_settings();
  s.depth_map_factor = 1000;
  EXPECT_FLOAT_EQ(open_dataset(seq, s)->load(0).depth.at<float>(5, 5), 5.0f);
}

TEST(TumDataset, ImageSizeMustMatchSettings) {
  TempDir dir;
  const fs::path seq = test::write_tum_fixture(dir.path(), 2);
  CameraSettings s = tum_settings();
  s.camera.width = 640;
  s.camera.height = 480;
  const std::string m = error_of([&] { open_dataset(seq, s)->load(0); });
  EXPECT_NE(m.find("rgb/100.000000.png: image is 64x48 but the settings say Camera.width/height 640x480"),
            std::string::npos)
      << m;
  s.camera.width = 64;
  s.camera.height = 48;
  EXPECT_TRUE(open_dataset(seq, s)->load(0).valid);
}

// Concurrent load() calls on one dataset give the same frames as serial ones.
TEST(TumDataset, ConcurrentLoads) {
  TempDir dir;
  const fs::path seq = test::write_tum_fixture(dir.path(), 8);
  const auto d = open_dataset(seq, tum_settings());
  std::vector<SensorFrame> serial;
  for (std::size_t i = 0; i < d->size(); ++i) serial.push_back(d->load(i));
  std::vector<SensorFrame> a(d->size()), b(d->size());
  std::thread ta([&] {
    for (std::size_t i = 0; i < d->size(); ++i) a[i] = d->load(i);
  });
  std::thread tb([&] {
    for (std::size_t i = d->size(); i-- > 0;) b[i] = d->load(i);
  });
  ta.join();
  tb.join();
  for (std::size_t i = 0; i < d->size(); ++i) {
    EXPECT_EQ(cv::norm(a[i].color, serial[i].color, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(b[i].depth, serial[i].depth, cv::NORM_INF), 0.0);
  }
}

TEST(TumDataset, AssociationFileAutodetectedAndOption) {
  TempDir dir;
  const fs::path seq = test::write_tum_fixture(dir.path(), 4);
  // Depth-first column order, only two frames.
  dir.write(seq.lexically_relative(dir.path()) / "associations.txt",
            "100.037333 depth/100.037333.png 100.033333 rgb/100.033333.png\n"
            "100.070667 depth/100.070667.png 100.066667 rgb/100.066667.png\n");
  {
    const auto d = open_dataset(seq, tum_settings());
    ASSERT_EQ(d->size(), 2u);
    EXPECT_DOUBLE_EQ(d->timestamp(0), 100.033333);  // rgb time
    EXPECT_EQ(d->load(1).name, "rgb/100.066667.png");
  }
  const fs::path custom = dir.write("lists/one.txt", "100.000000 rgb/100.000000.png 100.004000 depth/100.004000.png\n");
  {
    DatasetOptions options;
    options.association_file = custom;
    const auto d = open_dataset(seq, tum_settings(), options);
    ASSERT_EQ(d->size(), 1u);
    EXPECT_FLOAT_EQ(d->load(0).depth.at<float>(1, 1), 1.0f);
  }
  {  // An association file given as the input path.
    fs::copy_file(custom, seq / "walking.txt");
    const auto d = open_dataset(seq / "walking.txt", tum_settings());
    ASSERT_EQ(d->size(), 1u);
    EXPECT_EQ(d->load(0).name, "rgb/100.000000.png");
  }
}

TEST(TumDataset, MaxDtOption) {
  TempDir dir;
  const fs::path seq = test::write_tum_fixture(dir.path(), 4);
  DatasetOptions options;
  options.max_dt = 0.003;  // depth is 4 ms after rgb
  EXPECT_NE(error_of([&] { open_dataset(seq, tum_settings(), options); }).find("no frames"), std::string::npos);
  options.max_dt = 0.005;
  EXPECT_EQ(open_dataset(seq, tum_settings(), options)->size(), 4u);
}

TEST(TumDataset, BadFramesAreClearErrors) {
  TempDir dir;
  const fs::path seq = test::write_tum_fixture(dir.path(), 5);
  fs::remove(seq / "rgb" / "100.033333.png");                                       // frame 1: missing
  test::truncate_copy(seq / "rgb" / "100.100000.png", seq / "rgb" / "tmp.png", 0.5);  // frame 3: truncated
  fs::rename(seq / "rgb" / "tmp.png", seq / "rgb" / "100.100000.png");
  cv::imwrite((seq / "depth" / "100.137333.png").string(), cv::Mat(48, 64, CV_8UC1, cv::Scalar(7)));  // frame 4

  const auto d = open_dataset(seq, tum_settings());
  ASSERT_EQ(d->size(), 5u);
  EXPECT_NO_THROW(d->load(0));
  std::string m = error_of([&] { d->load(1); });
  EXPECT_NE(m.find("rgb/100.033333.png: image file is missing"), std::string::npos) << m;
  m = error_of([&] { d->load(3); });
  EXPECT_NE(m.find("rgb/100.100000.png: cannot decode image"), std::string::npos) << m;
  m = error_of([&] { d->load(4); });
  EXPECT_NE(m.find("depth/100.137333.png: depth must be a 16-bit single-channel PNG"), std::string::npos) << m;
  EXPECT_NE(m.find("DepthMapFactor"), std::string::npos) << m;
  m = error_of([&] { d->load(5); });
  EXPECT_NE(m.find("index 5 is out of range (the sequence has 5 frames)"), std::string::npos) << m;
  EXPECT_EQ(d->skipped_frames(), 0u);

  DatasetOptions skip;
  skip.skip_bad_frames = true;
  const auto s = open_dataset(seq, tum_settings(), skip);
  int valid = 0;
  for (std::size_t i = 0; i < s->size(); ++i) {
    const SensorFrame f = s->load(i);
    EXPECT_EQ(f.index, i);
    EXPECT_DOUBLE_EQ(f.timestamp, s->timestamp(i));
    if (f.valid) {
      ++valid;
      EXPECT_FALSE(f.color.empty());
    } else {
      EXPECT_TRUE(f.color.empty());
      EXPECT_FALSE(f.error.empty());
      EXPECT_FALSE(f.name.empty());
    }
  }
  EXPECT_EQ(valid, 2);
  EXPECT_EQ(s->skipped_frames(), 3u);
  EXPECT_THROW(s->load(5), Error);  // a bad index is never skipped
}

TEST(TumDataset, EmptyOrMalformedLists) {
  TempDir dir;
  const fs::path seq = test::write_tum_fixture(dir.path(), 2);
  std::ofstream(seq / "rgb.txt") << "# color images\n";
  std::string m = error_of([&] { open_dataset(seq, tum_settings()); });
  EXPECT_NE(m.find("rgb.txt: no frames"), std::string::npos) << m;
  std::ofstream(seq / "rgb.txt") << "100.0 rgb/100.000000.png\nabc rgb/x.png\n";
  m = error_of([&] { open_dataset(seq, tum_settings()); });
  EXPECT_NE(m.find("rgb.txt:2: expected a number, got 'abc'"), std::string::npos) << m;
  fs::remove(seq / "depth.txt");
  m = error_of([&] { open_dataset(seq, tum_settings()); });
  EXPECT_NE(m.find("depth.txt: missing"), std::string::npos) << m;
}

TEST(OpenDataset, UnknownLayoutListsWhatWasLookedFor) {
  TempDir dir;
  dir.write("something/readme.txt", "hello");
  const std::string m = error_of([&] { open_dataset(dir.path() / "something", tum_settings()); });
  EXPECT_NE(m.find("no known dataset layout"), std::string::npos) << m;
  EXPECT_NE(m.find("rgb.txt + depth.txt"), std::string::npos) << m;
  EXPECT_NE(m.find("mav0/cam0/data.csv"), std::string::npos) << m;
  EXPECT_NE(m.find("times.txt + image_0/"), std::string::npos) << m;
  EXPECT_NE(error_of([&] { open_dataset(dir.path() / "nope", tum_settings()); }).find("dataset folder not found"),
            std::string::npos);
}

}  // namespace
}  // namespace stillslam
