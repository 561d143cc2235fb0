#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "stillslam/features/descriptor.h"
#include "stillslam/features/descriptor_matcher.h"

namespace stillslam {

TEST(DescriptorDistance, CountsConstructedBits) {
  cv::Mat a = cv::Mat::zeros(1, 32, CV_8UC1), b = cv::Mat::zeros(1, 32, CV_8UC1);
  EXPECT_EQ(descriptor_distance(a, b), 0);
  b.at<std::uint8_t>(0, 0) = 0x01;
  EXPECT_EQ(descriptor_distance(a, b), 1);
  b.at<std::uint8_t>(0, 31) = 0x80;
  b.at<std::uint8_t>(0, 13) = 0xF0;
  EXPECT_EQ(descriptor_distance(a, b), 6);
  b.setTo(0xFF);
  EXPECT_EQ(descriptor_distance(a, b), 256);
  a.setTo(0xAA);
  b.setTo(0x55);
  EXPECT_EQ(descriptor_distance(a, b), 256);
  b.setTo(0xAB);  // one bit differs per byte
  EXPECT_EQ(descriptor_distance(a.ptr<std::uint8_t>(), b.ptr<std::uint8_t>()), 32);
}

TEST(DescriptorDistance, MatchesOpenCvHammingOnRandomRows) {
  cv::RNG rng(5);
  cv::Mat m(200, 32, CV_8UC1);
  rng.fill(m, cv::RNG::UNIFORM, 0, 256);
  for (int i = 0; i + 1 < m.rows; ++i) {
    const int expected = static_cast<int>(cv::norm(m.row(i), m.row(i + 1), cv::NORM_HAMMING));
    EXPECT_EQ(descriptor_distance(m.row(i), m.row(i + 1)), expected);
  }
}

TEST(DescriptorMatcher, FindsPermutedNoisyCopies) {
  cv::RNG rng(9);
  cv::Mat query(100, 32, CV_8UC1);
  rng.fill(query, cv::RNG::UNIFORM, 0, 256);
  cv::Mat train(100, 32, CV_8UC1);
  // train row (i * 37) % 100 is query row i with 10 bits flipped.
  for (int i = 0; i < 100; ++i) {
    cv::Mat row = query.row(i).clone();
    for (int k = 0; k < 10; ++k) row.at<std::uint8_t>(0, (k * 3 + i) % 32) ^= static_cast<std::uint8_t>(1u << (k % 8));
    row.copyTo(train.row((i * 37) % 100));
  }
  const auto matches = match_descriptors(query, train, {.max_distance = 50, .ratio = 0.8f, .cross_check = true});
  ASSERT_EQ(matches.size(), 100u);
  for (const auto& m : matches) {
    EXPECT_EQ(m.trainIdx, (m.queryIdx * 37) % 100);
    EXPECT_LE(m.distance, 10.f);
  }
  // A strict distance gate removes everything.
  EXPECT_TRUE(match_descriptors(query, train, {.max_distance = 5}).empty());
}

TEST(RotationConsistency, KeepsTheDominantBins) {
  std::vector<float> diffs;
  for (int i = 0; i < 50; ++i) diffs.push_back(90.f + static_cast<float>(i % 5));  // bin 7 (84..96)
  for (int i = 0; i < 8; ++i) diffs.push_back(-265.f);  // = 95 deg, same bin
  for (int i = 0; i < 10; ++i) diffs.push_back(100.f);  // bin 8: 10 >= 10% of 58
  for (int i = 0; i < 4; ++i) diffs.push_back(200.f);   // bin 16: 4 < 10% of 58
  diffs.push_back(300.f);                                // bin 25: singletons lose
  const std::vector<bool> keep = rotation_consistent(diffs, 30);
  int kept = 0;
  for (bool k : keep) kept += k;
  EXPECT_EQ(kept, 68);
  EXPECT_TRUE(keep[0]);
  EXPECT_TRUE(keep[50]);
  EXPECT_TRUE(keep[58]);
  EXPECT_FALSE(keep[68]);
  EXPECT_FALSE(keep.back());
}

}  // namespace stillslam
