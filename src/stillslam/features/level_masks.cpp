#include "stillslam/features/level_masks.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace stillslam {

std::vector<cv::Mat1b> level_masks(const cv::Mat1b& mask, const std::vector<cv::Size>& sizes) {
  std::vector<cv::Mat1b> out(sizes.size());
  if (sizes.empty()) return out;
  out[0] = mask;
  const cv::Rect box = cv::boundingRect(mask);
  cv::Mat1i integral;  // of the box: (box.height + 1) x (box.width + 1)
  if (!box.empty()) cv::integral(mask(box), integral, CV_32S);
  for (std::size_t l = 1; l < sizes.size(); ++l) {
    const cv::Size size = sizes[l];
    if (size.width <= 0 || size.height <= 0) continue;
    out[l] = cv::Mat1b(size, uchar{0});
    if (box.empty()) continue;
    const double sx = static_cast<double>(mask.cols) / size.width, sy = static_cast<double>(mask.rows) / size.height;
    // A level coordinate's footprint [first, last) in box coordinates (empty when outside the box).
    const auto span = [](int i, double s, int origin, int extent) {
      const int first = std::clamp(static_cast<int>(std::floor(i * s)) - origin, 0, extent);
      const int last = std::clamp(static_cast<int>(std::ceil((i + 1) * s)) - origin, 0, extent);
      return std::make_pair(first, last);
    };
    const int x_begin = std::max(0, static_cast<int>(std::floor(box.x / sx)) - 1);
    const int x_end = std::min(size.width, static_cast<int>(std::ceil((box.x + box.width) / sx)) + 1);
    const int y_begin = std::max(0, static_cast<int>(std::floor(box.y / sy)) - 1);
    const int y_end = std::min(size.height, static_cast<int>(std::ceil((box.y + box.height) / sy)) + 1);
    for (int y = y_begin; y < y_end; ++y) {
      const auto [y0, y1] = span(y, sy, box.y, box.height);
      if (y0 >= y1) continue;
      const int* top = integral.ptr<int>(y0);
      const int* bottom = integral.ptr<int>(y1);
      uchar* row = out[l].ptr<uchar>(y);
      for (int x = x_begin; x < x_end; ++x) {
        const auto [x0, x1] = span(x, sx, box.x, box.width);
        if (x0 >= x1) continue;
        if (bottom[x1] - bottom[x0] - top[x1] + top[x0] > 0) row[x] = 255;
      }
    }
  }
  return out;
}

}  // namespace stillslam
