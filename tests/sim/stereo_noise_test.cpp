// The rectified stereo pair (EuRoC layout) and the sensor noise models.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <random>

#include "stillslam/io/dataset.h"
#include "stillslam/io/camera_settings.h"
#include "stillslam/sim/noise.h"
#include "stillslam/sim/sequence_writer.h"
#include "stillslam/sim/simulator.h"

namespace stillslam::sim {
namespace {
namespace fs = std::filesystem;

SimulationOptions small_options() {
  SimulationOptions o;
  o.width = 320;
  o.height = 240;
  o.frames = 2;
  o.people = 1;
  o.trajectory = "rpy";
  o.data_dir = fs::path(STILLSLAM_SOURCE_DIR) / "data";
  return o;
}

TEST(Stereo, RightImageIsTheLeftShiftedByTheDisparity) {
  SimulationOptions o = small_options();
  o.stereo = true;
  o.people = 0;
  const Simulator sim(o);
  const SimFrame f = sim.render_frame(0);
  ASSERT_EQ(f.right_gray.type(), CV_8UC1);
  cv::Mat left;
  cv::cvtColor(f.bgr, left, cv::COLOR_BGR2GRAY);
  const double fx = sim.camera().fx;
  double shifted = 0, unshifted = 0;
  int n = 0;
  for (int v = 20; v < o.height - 20; v += 3) {
    for (int u = 60; u < o.width - 10; u += 3) {
      const float z = f.depth.at<float>(v, u);
      ASSERT_GT(z, 0);
      const double d = fx * o.baseline / z;  // disparity, pixels
      if (u - d < 2) continue;
      cv::Mat px;
      cv::getRectSubPix(f.right_gray, {1, 1}, cv::Point2f(static_cast<float>(u - d), static_cast<float>(v)), px,
                        CV_32F);
      shifted += std::abs(px.at<float>(0, 0) - left.at<uchar>(v, u));
      unshifted += std::abs(double(f.right_gray.at<uchar>(v, u)) - left.at<uchar>(v, u));
      ++n;
    }
  }
  ASSERT_GT(n, 3000);
  EXPECT_LT(shifted / n, 6.0);             // same surface point: same grey (up to edges/resampling)
  EXPECT_GT(unshifted / n, 2.5 * shifted / n);  // and the shift really matters
}

TEST(Stereo, EurocLayoutLoadsWithItsSettings) {
  const fs::path dir = fs::temp_directory_path() / ("stillslam_sim_stereo_" + std::to_string(std::random_device{}()));
  SimulationOptions o = small_options();
  o.stereo = true;
  o.frames = 3;
  const SequenceSummary s = write_sequence(dir, o);
  ASSERT_FALSE(s.settings_stereo.empty());
  const CameraSettings settings = load_camera_settings(s.settings_stereo);
  ASSERT_TRUE(settings.stereo.has_value());
  const auto dataset = open_dataset(dir, settings);
  EXPECT_EQ(dataset->kind(), "euroc");
  ASSERT_EQ(dataset->size(), 3u);
  const auto rect = dataset->rectified_stereo();
  ASSERT_TRUE(rect.has_value());
  EXPECT_NEAR(rect->baseline, 0.1, 1e-6);
  EXPECT_NEAR(rect->left.fx, camera_from_options(o).fx, 0.5);
  const SensorFrame f = dataset->load(1);
  EXPECT_EQ(f.gray.size(), cv::Size(320, 240));
  EXPECT_EQ(f.right.size(), cv::Size(320, 240));
  EXPECT_EQ(f.right.type(), CV_8UC1);
  // The left image comes in colour (for the segmenter): the rgb/ image itself.
  const auto tum = open_dataset(dir, load_camera_settings(s.settings));
  EXPECT_EQ(tum->kind(), "tum");  // the RGB-D layout in the same folder still opens as TUM
  const SensorFrame rgbd = tum->load(1);
  ASSERT_EQ(f.color.type(), CV_8UC3);
  EXPECT_EQ(cv::norm(f.color, rgbd.color, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(f.gray, rgbd.gray, cv::NORM_INF), 0.0);

  // --gray-stereo: EuRoC-like monochrome files, the same gray images, no colour.
  const fs::path gray_dir = dir.string() + "_gray";
  o.stereo_gray = true;
  write_sequence(gray_dir, o);
  const SensorFrame g = open_dataset(gray_dir, settings)->load(1);
  EXPECT_EQ(cv::norm(g.gray, f.gray, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(g.right, f.right, cv::NORM_INF), 0.0);
  std::vector<cv::Mat> channels;
  cv::split(g.color, channels);
  ASSERT_EQ(channels.size(), 3u);
  EXPECT_EQ(cv::norm(channels[0], channels[2], cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(f.color, g.color, cv::NORM_L1) / f.color.total(), 5.0);  // colour really was dropped
  fs::remove_all(dir);
  fs::remove_all(gray_dir);
}

TEST(Noise, DepthNoiseGrowsWithTheSquareOfDepth) {
  cv::RNG rng(3);
  const NoiseModel m = noise_model(1);
  for (double z : {1.0, 2.0, 3.0}) {
    const cv::Mat depth(200, 200, CV_32FC1, cv::Scalar(z));
    const cv::Mat noisy = apply_depth_noise(depth, m, rng);
    cv::Mat valid = noisy > 0;
    cv::Scalar mean, stddev;
    cv::meanStdDev(noisy, mean, stddev, valid);
    EXPECT_NEAR(stddev[0], m.depth_k * z * z, 0.1 * m.depth_k * z * z) << z;
    EXPECT_NEAR(mean[0], z, 0.01);
    // Random dropouts only (no edges, in range): ~0.2%.
    EXPECT_NEAR(1.0 - cv::countNonZero(valid) / 40000.0, m.dropout_prob, 0.002);
  }
  // Beyond the range limit depth is missing.
  const cv::Mat far(10, 10, CV_32FC1, cv::Scalar(m.max_range + 0.5));
  EXPECT_EQ(cv::countNonZero(apply_depth_noise(far, m, rng)), 0);
}

TEST(Noise, DepthEdgesLoseTheirDepth) {
  cv::RNG rng(5);
  NoiseModel m = noise_model(2);
  m.dropout_prob = 0;
  cv::Mat depth(50, 100, CV_32FC1, cv::Scalar(3.0));
  depth.colRange(0, 50).setTo(1.0);  // a step at column 50
  const cv::Mat noisy = apply_depth_noise(depth, m, rng);
  EXPECT_EQ(cv::countNonZero(noisy.col(49)), 0);
  EXPECT_EQ(cv::countNonZero(noisy.col(50)), 0);
  EXPECT_EQ(cv::countNonZero(noisy.col(20)), 50);
  EXPECT_EQ(cv::countNonZero(noisy.col(80)), 50);
}

TEST(Noise, LevelOneChangesImagesAndPunchesDepthHoles) {
  SimulationOptions clean = small_options();
  clean.trajectory = "halfsphere";
  clean.people = 0;
  SimulationOptions noisy = clean;
  noisy.noise = 1;
  const SimFrame a = Simulator(clean).render_frame(1), b = Simulator(noisy).render_frame(1);
  EXPECT_EQ(a.T_world_cam.matrix(), b.T_world_cam.matrix());
  // Motion blur and noise: the image differs everywhere a bit.
  cv::Mat ga, gb, diff;
  cv::cvtColor(a.bgr, ga, cv::COLOR_BGR2GRAY);
  cv::cvtColor(b.bgr, gb, cv::COLOR_BGR2GRAY);
  cv::absdiff(ga, gb, diff);
  EXPECT_GT(cv::mean(diff)[0], 1.0);
  EXPECT_GT(cv::countNonZero(a.depth), cv::countNonZero(b.depth));  // holes appear
}

}  // namespace
}  // namespace stillslam::sim
