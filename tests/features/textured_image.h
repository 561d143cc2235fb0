#pragma once
// Deterministic, procedurally textured test images: overlapping random
// polygons and discs of many sizes and grey levels over a smooth noise
// background, lightly blurred like a camera image. cv::RNG is specified
// exactly, so the image is the same on every platform. Small max_size and
// many shapes give a statistically uniform texture.
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace stillslam::test {

inline cv::Mat textured_image(int width = 640, int height = 480, std::uint64_t seed = 42,
                              int shapes = 900, double max_size = 70.0) {
  cv::RNG rng(seed);
  cv::Mat noise(height / 8 + 1, width / 8 + 1, CV_8UC1);
  rng.fill(noise, cv::RNG::UNIFORM, 60, 200);
  cv::Mat image;
  cv::resize(noise, image, cv::Size(width, height), 0, 0, cv::INTER_CUBIC);
  for (int i = 0; i < shapes; ++i) {
    const double size = std::exp(rng.uniform(std::log(4.0), std::log(max_size)));
    const cv::Point2d c(rng.uniform(0.0, static_cast<double>(width)), rng.uniform(0.0, static_cast<double>(height)));
    const cv::Scalar grey(rng.uniform(0, 256));
    if (rng.uniform(0, 3) == 0) {
      cv::circle(image, c, static_cast<int>(size / 2), grey, cv::FILLED, cv::LINE_AA);
    } else {
      const int n = rng.uniform(3, 6);
      std::vector<cv::Point> poly;
      const double phase = rng.uniform(0.0, 6.283);
      for (int k = 0; k < n; ++k) {
        const double a = phase + 6.283 * k / n + rng.uniform(-0.4, 0.4);
        const double r = size * rng.uniform(0.4, 1.0);
        poly.emplace_back(cvRound(c.x + r * std::cos(a)), cvRound(c.y + r * std::sin(a)));
      }
      cv::fillConvexPoly(image, poly, grey, cv::LINE_AA);
    }
  }
  cv::GaussianBlur(image, image, cv::Size(0, 0), 0.8);
  return image;
}

}  // namespace stillslam::test
