#include <gtest/gtest.h>

#include <cmath>

#include "stillslam/features/feature_grid.h"

namespace stillslam {
namespace {

std::vector<std::size_t> brute_force(const std::vector<cv::KeyPoint>& kps, const cv::Rect2f& bounds,
                                     float x, float y, float r, int min_level, int max_level) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < kps.size(); ++i) {
    const auto& k = kps[i];
    if (k.pt.x < bounds.x || k.pt.y < bounds.y || k.pt.x >= bounds.x + bounds.width ||
        k.pt.y >= bounds.y + bounds.height) {
      continue;
    }
    if (min_level >= 0 && k.octave < min_level) continue;
    if (max_level >= 0 && k.octave > max_level) continue;
    if (std::abs(k.pt.x - x) < r && std::abs(k.pt.y - y) < r) out.push_back(i);
  }
  return out;
}

}  // namespace

TEST(FeatureGrid, EqualsBruteForceOnRandomQueries) {
  cv::RNG rng(3);
  // Undistorted bounds extend past the image (negative origin), and some
  // keypoints fall outside them.
  const cv::Rect2f bounds(-12.5f, -8.f, 660.f, 495.f);
  std::vector<cv::KeyPoint> kps;
  for (int i = 0; i < 3000; ++i) {
    kps.emplace_back(cv::Point2f(rng.uniform(-30.f, 670.f), rng.uniform(-30.f, 510.f)), 31.f, 0.f, 0.f,
                     rng.uniform(0, 8));
  }
  const FeatureGrid grid(kps, bounds);
  int total = 0;
  for (int q = 0; q < 500; ++q) {
    const float x = rng.uniform(-40.f, 680.f), y = rng.uniform(-40.f, 520.f);
    const float r = rng.uniform(0.5f, 80.f);
    const int min_level = rng.uniform(-1, 4), max_level = rng.uniform(-1, 8);
    const auto got = grid.features_in_area(x, y, r, min_level, max_level);
    const auto expected = brute_force(kps, bounds, x, y, r, min_level, max_level);
    ASSERT_EQ(got, expected) << "query " << q;
    total += static_cast<int>(got.size());
  }
  EXPECT_GT(total, 5000);  // queries actually return points
}

TEST(FeatureGrid, CellOfAndExactBoundaries) {
  std::vector<cv::KeyPoint> kps = {cv::KeyPoint(10.f, 10.f, 1.f), cv::KeyPoint(20.f, 10.f, 1.f)};
  const FeatureGrid grid(kps, cv::Rect2f(0, 0, 640, 480));
  int c = -1, r = -1;
  ASSERT_TRUE(grid.cell_of({639.9f, 479.9f}, &c, &r));
  EXPECT_EQ(c, 63);
  EXPECT_EQ(r, 47);
  EXPECT_FALSE(grid.cell_of({640.f, 10.f}, &c, &r));
  EXPECT_FALSE(grid.cell_of({-0.1f, 10.f}, &c, &r));
  // Strict inequality: a point exactly r away is outside.
  EXPECT_EQ(grid.features_in_area(15.f, 10.f, 5.f).size(), 0u);
  EXPECT_EQ(grid.features_in_area(15.f, 10.f, 5.01f).size(), 2u);
}

TEST(FeatureGrid, QueriesPastTheBoundsCrowdedCellsAndNoKeypoints) {
  // 50 keypoints in one cell (10 x 10 pixels), by index 0..49, levels 0..4.
  std::vector<cv::KeyPoint> kps;
  for (int i = 0; i < 50; ++i) {
    kps.emplace_back(cv::Point2f(100.f + 0.1f * static_cast<float>(i), 200.f + 0.05f * static_cast<float>(i)), 31.f,
                     0.f, 0.f, i % 5);
  }
  const FeatureGrid grid(kps, cv::Rect2f(0, 0, 640, 480));
  const auto all = grid.features_in_area(102.f, 201.f, 5.f);
  ASSERT_EQ(all.size(), 50u);
  for (std::size_t i = 0; i < all.size(); ++i) EXPECT_EQ(all[i], i);  // ascending indices
  const auto level2 = grid.features_in_area(102.f, 201.f, 5.f, 2, 2);
  ASSERT_EQ(level2.size(), 10u);
  EXPECT_EQ(level2.front(), 2u);
  EXPECT_EQ(level2.back(), 47u);
  // Windows wholly left of, right of, above or below the bounds.
  EXPECT_TRUE(grid.features_in_area(-300.f, 200.f, 50.f).empty());
  EXPECT_TRUE(grid.features_in_area(1000.f, 200.f, 50.f).empty());
  EXPECT_TRUE(grid.features_in_area(100.f, -300.f, 50.f).empty());
  EXPECT_TRUE(grid.features_in_area(100.f, 900.f, 50.f).empty());
  // A window covering the whole image returns every keypoint once.
  EXPECT_EQ(grid.features_in_area(0.f, 0.f, 1e6f).size(), 50u);
  const FeatureGrid empty(std::vector<cv::KeyPoint>{}, cv::Rect2f(0, 0, 640, 480));
  EXPECT_TRUE(empty.features_in_area(320.f, 240.f, 1000.f).empty());
}

}  // namespace stillslam
