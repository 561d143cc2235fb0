#pragma once
// Pixel coordinates between pyramid level images and the full-resolution
// image. A bilinear resize aligns pixel centres, so level pixel x covers
// full-resolution x0 = (x + 0.5) * ratio - 0.5, where ratio is the actual
// size ratio (e.g. 640 / 179 at level 7, not 1.2^7: sizes are rounded).
// Using x * 1.2^l instead shifts level-7 keypoints by up to ~2.5 px.
#include <opencv2/core.hpp>

namespace stillslam {

struct LevelMapping {
  float ratio_x = 1.f, ratio_y = 1.f;  // full size / level size

  LevelMapping() = default;
  LevelMapping(const cv::Size& full, const cv::Size& level)
      : ratio_x(static_cast<float>(full.width) / static_cast<float>(level.width)),
        ratio_y(static_cast<float>(full.height) / static_cast<float>(level.height)) {}

  cv::Point2f to_full(const cv::Point2f& p) const {
    return {(p.x + 0.5f) * ratio_x - 0.5f, (p.y + 0.5f) * ratio_y - 0.5f};
  }
  cv::Point2f to_level(const cv::Point2f& p) const {
    return {(p.x + 0.5f) / ratio_x - 0.5f, (p.y + 0.5f) / ratio_y - 0.5f};
  }
};

}  // namespace stillslam
