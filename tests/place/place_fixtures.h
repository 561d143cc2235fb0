#pragma once
// Shared fixtures for place/ tests: procedural images (same texture as the
// features tests), their ORB features, and a small vocabulary trained on them.
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "features/textured_image.h"
#include "stillslam/features/orb_extractor.h"
#include "stillslam/place/vocabulary.h"

namespace stillslam::test {

inline OrbFeatures orb_of(const cv::Mat& gray, int n_features = 500) {
  OrbOptions o;
  o.n_features = n_features;
  return OrbExtractor(o).extract(gray);
}

// `count` unrelated textured scenes (seed 100, 101, ...).
inline std::vector<cv::Mat> scene_images(int count, int width = 480, int height = 360) {
  std::vector<cv::Mat> images;
  for (int i = 0; i < count; ++i)
    images.push_back(textured_image(width, height, 100 + static_cast<std::uint64_t>(i), 600, 60.0));
  return images;
}

// The image moved by (dx, dy) pixels and rotated by `degrees` about its
// centre, border replicated: a small camera motion.
inline cv::Mat moved(const cv::Mat& image, double dx, double dy, double degrees) {
  cv::Mat m = cv::getRotationMatrix2D(cv::Point2f(image.cols / 2.f, image.rows / 2.f), degrees, 1.0);
  m.at<double>(0, 2) += dx;
  m.at<double>(1, 2) += dy;
  cv::Mat out;
  cv::warpAffine(image, out, m, image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  return out;
}

inline std::vector<cv::Mat> descriptors_of(const std::vector<cv::Mat>& images, int n_features = 500) {
  std::vector<cv::Mat> d;
  for (const auto& im : images) d.push_back(orb_of(im, n_features).descriptors);
  return d;
}

inline VocabularyOptions small_options(std::uint64_t seed = 0) {
  VocabularyOptions o;
  o.branching = 8;
  o.levels = 4;
  o.seed = seed;
  return o;
}

}  // namespace stillslam::test
