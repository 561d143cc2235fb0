#include <gtest/gtest.h>

#include "stillslam/core/error.h"
#include "stillslam/features/orb_extractor.h"
#include "stillslam/features/pyramid_coordinates.h"
#include "stillslam/features/scale_pyramid.h"

namespace stillslam {

TEST(ScalePyramid, ScalesAndSigmas) {
  const ScalePyramid p(OrbOptions{});
  ASSERT_EQ(p.n_levels, 8);
  EXPECT_FLOAT_EQ(p.scale[0], 1.f);
  EXPECT_NEAR(p.scale[1], 1.2f, 1e-6);
  EXPECT_NEAR(p.scale[7], 3.5831808f, 1e-5);
  EXPECT_NEAR(p.sigma2[2], 1.44f * 1.44f, 1e-5);
  EXPECT_NEAR(p.inv_scale[7] * p.scale[7], 1.f, 1e-6);
  EXPECT_NEAR(p.inv_sigma2[3] * p.sigma2[3], 1.f, 1e-6);
}

TEST(ScalePyramid, LevelForScale) {
  const ScalePyramid p(8, 1.2f);
  EXPECT_EQ(p.level_for_scale(0.5f), 0);
  EXPECT_EQ(p.level_for_scale(1.0f), 0);
  EXPECT_EQ(p.level_for_scale(1.1f), 1);
  EXPECT_EQ(p.level_for_scale(1.44f), 2);
  EXPECT_EQ(p.level_for_scale(1.5f), 3);
  EXPECT_EQ(p.level_for_scale(100.f), 7);
}

TEST(ScalePyramid, RejectsBadOptions) {
  EXPECT_THROW(ScalePyramid(0, 1.2f), Error);
  EXPECT_THROW(ScalePyramid(4, 1.0f), Error);
  EXPECT_NO_THROW(ScalePyramid(1, 1.0f));
  OrbOptions o;
  o.n_features = 0;
  EXPECT_THROW(OrbExtractor{o}, Error);
  o = {};
  o.ini_th_fast = 0;
  EXPECT_THROW(OrbExtractor{o}, Error);
}

TEST(ScalePyramid, FeaturesPerLevelIsAGeometricSeriesSummingToTotal) {
  OrbOptions o;
  o.n_features = 1000;
  const OrbExtractor extractor(o);
  const auto& n = extractor.features_per_level();
  ASSERT_EQ(n.size(), 8u);
  int sum = 0;
  for (int v : n) sum += v;
  EXPECT_EQ(sum, 1000);
  EXPECT_EQ(n[0], 217);  // 1000 * (1 - 1/1.2) / (1 - 1.2^-8)
  for (std::size_t l = 1; l + 1 < n.size(); ++l) EXPECT_NEAR(n[l] * 1.2, n[l - 1], 1.0);
}

TEST(ImagePyramid, LevelSizes) {
  const ScalePyramid p(8, 1.2f);
  const auto levels = build_image_pyramid(cv::Mat(480, 640, CV_8UC1, cv::Scalar(9)), p);
  ASSERT_EQ(levels.size(), 8u);
  EXPECT_EQ(levels[1].size(), cv::Size(533, 400));
  EXPECT_EQ(levels[7].size(), cv::Size(179, 134));
  EXPECT_EQ(levels[7].at<std::uint8_t>(50, 50), 9);
}

TEST(PyramidCoordinates, PixelCentresAndActualRatios) {
  const LevelMapping m(cv::Size(640, 480), cv::Size(179, 134));  // level 7 of 640x480
  const cv::Point2f full = m.to_full({0.f, 0.f});
  EXPECT_NEAR(full.x, 0.5f * 640.f / 179.f - 0.5f, 1e-5);
  EXPECT_NEAR(full.y, 0.5f * 480.f / 134.f - 0.5f, 1e-5);
  const cv::Point2f last = m.to_full({178.f, 133.f});  // last level pixel centre
  EXPECT_NEAR(last.x, 639.f - (0.5f * 640.f / 179.f - 0.5f), 1e-3);
  const cv::Point2f back = m.to_level(m.to_full({57.25f, 99.5f}));
  EXPECT_NEAR(back.x, 57.25f, 1e-4);
  EXPECT_NEAR(back.y, 99.5f, 1e-4);
  const LevelMapping identity(cv::Size(640, 480), cv::Size(640, 480));
  EXPECT_EQ(identity.to_full({12.f, 34.f}), cv::Point2f(12.f, 34.f));
}

}  // namespace stillslam
