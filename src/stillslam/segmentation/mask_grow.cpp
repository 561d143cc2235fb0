#include "stillslam/segmentation/mask_grow.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstring>
#include <vector>

#include "stillslam/core/row_runs.h"

namespace stillslam {

cv::Mat1b grow_mask(const cv::Mat1b& mask, int radius_px) {
  if (radius_px <= 0 || mask.empty()) return mask.clone();
  cv::Mat1b out(mask.size(), uchar{0});
  const cv::Rect box = cv::boundingRect(mask);
  if (box.empty()) return out;
  const int r = radius_px;
  // Half-width of the disc's row dy: the largest dx with dx^2 + dy^2 <= r^2.
  std::vector<int> half(static_cast<std::size_t>(r) + 1);
  for (int dy = 0, dx = r; dy <= r; ++dy) {
    while (dx * dx + dy * dy > r * r) --dx;
    half[static_cast<std::size_t>(dy)] = dx;
  }
  // Every run of set pixels in a row of the box paints its row dy away
  // widened by half[|dy|] (the union of the discs of its pixels): the disc
  // dilation, at a cost that grows with the mask's rows and runs, not with
  // the pixels times the disc's area.
  const int cols = mask.cols, rows = mask.rows;
  std::vector<std::pair<int, int>> runs;  // [first, last) in frame columns
  for (int y = box.y; y < box.y + box.height; ++y) {
    row_runs(mask.ptr<uchar>(y), box.x, box.x + box.width, runs);
    if (runs.empty()) continue;
    for (int dy = -r; dy <= r; ++dy) {
      const int yy = y + dy;
      if (yy < 0 || yy >= rows) continue;
      const int w = half[static_cast<std::size_t>(dy < 0 ? -dy : dy)];
      uchar* o = out.ptr<uchar>(yy);
      for (const auto& [first, last] : runs) {
        const int x0 = std::max(0, first - w), x1 = std::min(cols, last + w);
        std::memset(o + x0, 255, static_cast<std::size_t>(x1 - x0));
      }
    }
  }
  return out;
}

}  // namespace stillslam
