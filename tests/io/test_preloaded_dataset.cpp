// PreloadedDataset: the same frames as the source, the memory bound refused
// before decoding everything, and a bad frame failing where it would.
#include <gtest/gtest.h>

#include <atomic>

#include <opencv2/core.hpp>

#include "common/error_text.h"
#include "io/dataset_fixtures.h"
#include "io/temp_dir.h"
#include "stillslam/core/error.h"
#include "stillslam/io/dataset.h"
#include "stillslam/io/preloaded_dataset.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;
using test::contains;
using test::error_of;
using test::TempDir;

CameraSettings tum_settings() {
  CameraSettings s;
  s.camera.fx = s.camera.fy = 525;
  s.camera.cx = 32;
  s.camera.cy = 24;
  s.depth_map_factor = 5000;
  return s;
}

// Counts the frames a dataset was asked to decode.
class CountingDataset final : public Dataset {
 public:
  explicit CountingDataset(const Dataset& source) : source_(source) {}
  std::string kind() const override { return source_.kind(); }
  SensorType sensor() const override { return source_.sensor(); }
  std::size_t size() const override { return source_.size(); }
  double timestamp(std::size_t i) const override { return source_.timestamp(i); }
  SensorFrame load(std::size_t i) const override {
    ++loads;
    return source_.load(i);
  }
  mutable std::atomic<int> loads{0};

 private:
  const Dataset& source_;
};

bool same_pixels(const cv::Mat& a, const cv::Mat& b) {
  if (a.empty() || b.empty()) return a.empty() && b.empty();
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

TEST(PreloadedDataset, FramesAreTheSourceFrames) {
  TempDir dir;
  const auto source = open_dataset(test::write_tum_fixture(dir.path(), 5), tum_settings());
  CountingDataset counting(*source);
  const PreloadedDataset preloaded(counting, 1, 4, std::size_t{1} << 30);
  EXPECT_EQ(counting.loads.load(), 3);  // frames 1, 2, 3
  EXPECT_EQ(preloaded.frames(), 3u);
  // 64x48: colour 3 + gray 1 + depth 4 bytes a pixel.
  EXPECT_EQ(preloaded.bytes(), 3u * 64 * 48 * 8);
  EXPECT_EQ(preloaded.size(), 5u);
  EXPECT_EQ(preloaded.kind(), "tum");
  EXPECT_EQ(preloaded.sensor(), SensorType::Rgbd);
  for (std::size_t i = 0; i < 5; ++i) {
    const SensorFrame a = source->load(i);
    const SensorFrame b = preloaded.load(i);
    EXPECT_EQ(preloaded.timestamp(i), source->timestamp(i));
    EXPECT_EQ(b.index, a.index);
    EXPECT_EQ(b.timestamp, a.timestamp);
    EXPECT_EQ(b.name, a.name);
    EXPECT_TRUE(same_pixels(b.color, a.color)) << i;
    EXPECT_TRUE(same_pixels(b.gray, a.gray)) << i;
    EXPECT_TRUE(same_pixels(b.depth, a.depth)) << i;
    EXPECT_TRUE(b.right.empty());
  }
  // Frames 1-3 came from memory; 0 and 4 (outside the range) were decoded on demand.
  EXPECT_EQ(counting.loads.load(), 5);
}

TEST(PreloadedDataset, RefusesFramesOverTheBoundAfterDecodingOne) {
  TempDir dir;
  const auto source = open_dataset(test::write_tum_fixture(dir.path(), 5), tum_settings());
  CountingDataset counting(*source);
  const std::size_t frame = 64 * 48 * 8;
  const std::string message = error_of([&] { PreloadedDataset(counting, 0, 5, 5 * frame - 1); });
  EXPECT_EQ(counting.loads.load(), 1);  // the first frame's size times five was enough to refuse
  EXPECT_TRUE(contains(message, "preloading 5 frames")) << message;
  EXPECT_TRUE(contains(message, "--preload-limit-mb")) << message;
  // Exactly at the bound is accepted.
  EXPECT_EQ(PreloadedDataset(*source, 0, 5, 5 * frame).bytes(), 5 * frame);
}

TEST(PreloadedDataset, AnUnreadableFrameFailsWhereItWouldWithoutPreloading) {
  TempDir dir;
  const fs::path seq = test::write_tum_fixture(dir.path(), 5);
  const auto source = open_dataset(seq, tum_settings());
  const std::string name = source->load(2).name;
  fs::remove(seq / name);
  const std::string direct = error_of([&] { source->load(2); });
  ASSERT_FALSE(direct.empty());
  const PreloadedDataset preloaded(*source, 0, 5, std::size_t{1} << 30);
  EXPECT_EQ(preloaded.frames(), 2u);  // 0 and 1, then the missing file stopped it
  EXPECT_TRUE(same_pixels(preloaded.load(1).color, source->load(1).color));
  EXPECT_EQ(error_of([&] { preloaded.load(2); }), direct);
  EXPECT_TRUE(contains(direct, name)) << direct;
}

}  // namespace
}  // namespace stillslam
