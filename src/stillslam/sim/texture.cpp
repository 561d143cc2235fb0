#include "stillslam/sim/texture.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "stillslam/core/error.h"

namespace stillslam::sim {

MipTexture::MipTexture(const cv::Mat& image) {
  cv::Mat base;
  if (image.type() == CV_8UC3) {
    cv::cvtColor(image, base, cv::COLOR_BGR2BGRA);
  } else if (image.type() == CV_8UC4) {
    base = image.clone();
  } else {
    throw Error("sim texture: expected an 8-bit BGR or BGRA image");
  }
  levels_.push_back(base);
  while (levels_.back().cols >= 16 && levels_.back().rows >= 16) {
    cv::Mat next;
    cv::pyrDown(levels_.back(), next);
    levels_.push_back(next);
  }
}

Rgba MipTexture::sample(float x, float y, int level) const {
  const cv::Mat& img = levels_[std::clamp(level, 0, levels() - 1)];
  // Texel centres sit at (i + 0.5) / size.
  const float fx = x * img.cols - 0.5f;
  const float fy = y * img.rows - 0.5f;
  const int x0 = std::clamp(static_cast<int>(std::floor(fx)), 0, img.cols - 1);
  const int y0 = std::clamp(static_cast<int>(std::floor(fy)), 0, img.rows - 1);
  const int x1 = std::min(x0 + 1, img.cols - 1);
  const int y1 = std::min(y0 + 1, img.rows - 1);
  const float ax = std::clamp(fx - static_cast<float>(x0), 0.0f, 1.0f);
  const float ay = std::clamp(fy - static_cast<float>(y0), 0.0f, 1.0f);
  const cv::Vec4b* r0 = img.ptr<cv::Vec4b>(y0);
  const cv::Vec4b* r1 = img.ptr<cv::Vec4b>(y1);
  const float w00 = (1 - ax) * (1 - ay), w01 = ax * (1 - ay), w10 = (1 - ax) * ay, w11 = ax * ay;
  auto ch = [&](int c) {
    return w00 * r0[x0][c] + w01 * r0[x1][c] + w10 * r1[x0][c] + w11 * r1[x1][c];
  };
  return {ch(0), ch(1), ch(2), ch(3)};
}

bool MipTexture::opaque(float x, float y) const { return sample(x, y, 0).a >= 127.5f; }

}  // namespace stillslam::sim
