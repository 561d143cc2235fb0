#include "stillslam/segmentation/dynamic_mask.h"

#include <gtest/gtest.h>

#include "stillslam/core/error.h"

namespace stillslam {
namespace {

Detection with_mask(int class_id, cv::Size size, cv::Rect region) {
  Detection d;
  d.class_id = class_id;
  d.box = cv::Rect2f(region);
  d.mask = cv::Mat1b(size, uchar{0});
  d.mask(region).setTo(255);
  return d;
}

TEST(DynamicMask, UnionOfWantedClassesOnly) {
  const cv::Size size(100, 80);
  const std::vector<Detection> dets{with_mask(0, size, {10, 10, 20, 20}),   // person 400 px
                                    with_mask(56, size, {50, 10, 10, 30}),  // chair 300 px
                                    with_mask(5, size, {0, 60, 100, 20}),   // bus 2000 px
                                    with_mask(0, size, {20, 20, 20, 20})};  // person, overlaps the first by 100
  EXPECT_EQ(cv::countNonZero(dynamic_mask(dets, {0}, size, 0)), 700);
  EXPECT_EQ(cv::countNonZero(dynamic_mask(dets, {0, 56}, size, 0)), 1000);
  EXPECT_EQ(cv::countNonZero(dynamic_mask(dets, {}, size, 0)), 0);
  EXPECT_DOUBLE_EQ(mask_coverage(dynamic_mask(dets, {5}, size, 0)), 0.25);
}

TEST(DynamicMask, DilationGrowsByAnEllipseOfTheGivenRadius) {
  const cv::Size size(100, 80);
  const std::vector<Detection> dot{with_mask(0, size, {50, 40, 1, 1})};
  EXPECT_EQ(cv::countNonZero(dynamic_mask(dot, {0}, size, 0)), 1);
  EXPECT_EQ(cv::countNonZero(dynamic_mask(dot, {0}, size, 1)), 5);   // plus sign
  EXPECT_EQ(cv::countNonZero(dynamic_mask(dot, {0}, size, 2)), 13);  // dx^2 + dy^2 <= 4
  EXPECT_EQ(cv::countNonZero(dynamic_mask(dot, {0}, size, 3)), 29);  // dx^2 + dy^2 <= 9
  const std::vector<Detection> square{with_mask(0, size, {40, 30, 20, 20})};
  const cv::Mat1b grown = dynamic_mask(square, {0}, size, 2);
  EXPECT_EQ(grown(31, 38), 255);  // 2 px left of the square
  EXPECT_EQ(grown(31, 37), 0);    // 3 px left
  EXPECT_EQ(grown(29, 39), 255);  // 1 px diagonally off the corner (distance 1.41)
  EXPECT_EQ(grown(28, 38), 0);    // 2 px diagonally off the corner (distance 2.83)
  EXPECT_EQ(cv::countNonZero(grown), 20 * 20 + 4 * 20 * 2 + 4);  // square + 2 px bands + (1,1) at each corner
  EXPECT_EQ(grown(28, 40), 255);  // 2 px above
}

TEST(DynamicMask, DetectionsWithoutMaskUseTheirBox) {
  const cv::Size size(100, 80);
  Detection d;
  d.class_id = 0;
  d.box = cv::Rect2f(90.5f, 70.2f, 20.0f, 20.0f);  // partly outside the frame
  EXPECT_EQ(cv::countNonZero(dynamic_mask({d}, {0}, size, 0)), 10 * 10);
  Detection wrong = d;
  wrong.mask = cv::Mat1b(10, 10, uchar{255});
  EXPECT_THROW(dynamic_mask({wrong}, {0}, size, 0), Error);
}

TEST(KeypointFilter, ExactCountsOnASyntheticMask) {
  cv::Mat1b mask(80, 100, uchar{0});
  mask(cv::Rect(20, 10, 30, 20)).setTo(255);  // x 20..49, y 10..29
  std::vector<cv::KeyPoint> kps;
  for (int y = 0; y < 80; y += 5)
    for (int x = 0; x < 100; x += 5) kps.emplace_back(static_cast<float>(x), static_cast<float>(y), 7.0f);
  // 20x16 = 320 grid points; inside: x in {20..45} (6) times y in {10..25} (4) = 24.
  const auto keep = keypoints_outside_mask(kps, mask);
  EXPECT_EQ(keep.size(), 320u - 24u);
  EXPECT_TRUE(std::is_sorted(keep.begin(), keep.end()));

  // Rounding to the nearest pixel decides at the border; off-image keypoints are kept.
  const std::vector<cv::KeyPoint> edge{{19.4f, 15.f, 7.f}, {19.6f, 15.f, 7.f}, {49.4f, 29.4f, 7.f},
                                       {49.6f, 15.f, 7.f}, {-3.f, 15.f, 7.f},  {150.f, 500.f, 7.f}};
  EXPECT_EQ(keypoints_outside_mask(edge, mask), (std::vector<std::size_t>{0, 3, 4, 5}));
  EXPECT_EQ(keypoints_outside_mask(edge, cv::Mat1b()).size(), edge.size());
}

}  // namespace
}  // namespace stillslam
