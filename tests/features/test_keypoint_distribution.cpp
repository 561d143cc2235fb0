#include <gtest/gtest.h>

#include "stillslam/features/keypoint_distribution.h"

namespace stillslam {

TEST(KeypointDistribution, UniformInSpaceNotInDensity) {
  // Left half: 4000 dense corners; right half: 100 sparse ones.
  cv::RNG rng(11);
  std::vector<cv::KeyPoint> kps;
  for (int i = 0; i < 4000; ++i) kps.emplace_back(rng.uniform(0.f, 320.f), rng.uniform(0.f, 480.f), 7.f, 0.f, rng.uniform(1.f, 50.f));
  for (int i = 0; i < 100; ++i) kps.emplace_back(rng.uniform(320.f, 640.f), rng.uniform(0.f, 480.f), 7.f, 0.f, rng.uniform(1.f, 50.f));
  const auto kept = distribute_quadtree(kps, cv::Rect2f(0, 0, 640, 480), 200);
  ASSERT_EQ(kept.size(), 200u);
  int right = 0;
  for (std::size_t i : kept) right += kps[i].pt.x >= 320.f;
  // Density-proportional selection would give ~5 on the right; equal-area
  // nodes give the sparse half a large share of its 100 corners.
  EXPECT_GE(right, 60);
  EXPECT_TRUE(std::is_sorted(kept.begin(), kept.end()));
}

TEST(KeypointDistribution, KeepsStrongestPerNodeAndHandlesSmallInputs) {
  std::vector<cv::KeyPoint> kps = {cv::KeyPoint(10.f, 10.f, 7.f, 0.f, 5.f), cv::KeyPoint(10.5f, 10.f, 7.f, 0.f, 9.f),
                                   cv::KeyPoint(10.f, 10.f, 7.f, 0.f, 1.f)};  // duplicate position
  auto kept = distribute_quadtree(kps, cv::Rect2f(0, 0, 100, 100), 1);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0], 1u);
  kept = distribute_quadtree(kps, cv::Rect2f(0, 0, 100, 100), 10);
  EXPECT_EQ(kept.size(), 2u);  // the two identical positions cannot be separated
  EXPECT_TRUE(distribute_quadtree(kps, cv::Rect2f(50, 50, 10, 10), 10).empty());
  EXPECT_TRUE(distribute_quadtree({}, cv::Rect2f(0, 0, 10, 10), 10).empty());
}

}  // namespace stillslam
