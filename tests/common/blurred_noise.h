#pragma once
// A textured test image: uniform noise blurred (sigma 1.5 px) and stretched to
// 0..255, so FAST and ORB find corners everywhere and descriptors differ.
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace stillslam::test {

inline cv::Mat blurred_noise(int rows, int cols, int seed) {
  cv::Mat noise(rows, cols, CV_8U);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 255);
  cv::Mat img;
  cv::GaussianBlur(noise, img, cv::Size(0, 0), 1.5);
  cv::normalize(img, img, 0, 255, cv::NORM_MINMAX);
  return img;
}

}  // namespace stillslam::test
