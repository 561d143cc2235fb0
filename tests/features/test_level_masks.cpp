// level_masks (features/level_masks.h): a level pixel is excluded exactly
// when its full-resolution footprint holds a masked pixel (brute force), and
// every pixel INTER_AREA's resize keeps (> 0) is among them.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "stillslam/features/level_masks.h"

namespace stillslam {
namespace {

TEST(LevelMasks, AnyMaskedPixelInTheFootprintExcludesTheLevelPixel) {
  cv::Mat1b mask(480, 640, uchar{0});
  cv::circle(mask, {200, 240}, 80, 255, -1);
  cv::rectangle(mask, {400, 100}, {500, 400}, 255, -1);
  mask(7, 633) = 255;  // a lone pixel near a corner
  std::vector<cv::Size> sizes{mask.size()};
  double s = 1;
  for (int l = 1; l < 8; ++l) {
    s *= 1.2;
    sizes.emplace_back(static_cast<int>(std::lround(640 / s)), static_cast<int>(std::lround(480 / s)));
  }
  const std::vector<cv::Mat1b> levels = level_masks(mask, sizes);
  ASSERT_EQ(levels.size(), sizes.size());
  EXPECT_EQ(levels[0].data, mask.data);
  for (std::size_t l = 1; l < sizes.size(); ++l) {
    ASSERT_EQ(levels[l].size(), sizes[l]);
    const double sx = 640.0 / sizes[l].width, sy = 480.0 / sizes[l].height;
    int excluded = 0;
    for (int y = 0; y < sizes[l].height; ++y) {
      for (int x = 0; x < sizes[l].width; ++x) {
        const int x0 = static_cast<int>(std::floor(x * sx)), x1 = std::min(640, static_cast<int>(std::ceil((x + 1) * sx)));
        const int y0 = static_cast<int>(std::floor(y * sy)), y1 = std::min(480, static_cast<int>(std::ceil((y + 1) * sy)));
        const bool any = cv::countNonZero(mask(cv::Range(y0, y1), cv::Range(x0, x1))) > 0;
        ASSERT_EQ(levels[l](y, x) != 0, any) << "level " << l << " at " << x << "," << y;
        excluded += any;
      }
    }
    EXPECT_GT(excluded, 0);
    cv::Mat1b area;
    cv::resize(mask, area, sizes[l], 0, 0, cv::INTER_AREA);
    EXPECT_EQ(cv::countNonZero((area > 0) & (levels[l] == 0)), 0) << "level " << l;
  }
}

TEST(LevelMasks, AnEmptyMaskGivesEmptyLevels) {
  const cv::Mat1b mask(48, 64, uchar{0});
  const std::vector<cv::Mat1b> levels = level_masks(mask, {{64, 48}, {53, 40}, {0, 0}});
  EXPECT_EQ(cv::countNonZero(levels[1]), 0);
  EXPECT_EQ(levels[1].size(), cv::Size(53, 40));
  EXPECT_TRUE(levels[2].empty());
}

}  // namespace
}  // namespace stillslam
