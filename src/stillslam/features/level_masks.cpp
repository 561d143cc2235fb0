#include "stillslam/features/level_masks.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "stillslam/core/row_runs.h"

namespace stillslam {
namespace {

// For each full-resolution coordinate c in [0, extent): the first and last
// level coordinate i whose footprint [floor(i * s), ceil((i + 1) * s)) holds
// it. Footprints are ordered and cover [0, extent), so those i are one range,
// and the level coordinates a run [a, b) reaches are [first[a], last[b - 1]].
void footprint_ranges(int level_extent, int extent, double s, std::vector<int>& first, std::vector<int>& last) {
  first.assign(static_cast<std::size_t>(extent), std::numeric_limits<int>::max());
  last.assign(static_cast<std::size_t>(extent), -1);
  for (int i = 0; i < level_extent; ++i) {
    const int c0 = std::max(0, static_cast<int>(std::floor(i * s)));
    const int c1 = std::min(extent, static_cast<int>(std::ceil((i + 1) * s)));
    for (int c = c0; c < c1; ++c) {
      first[static_cast<std::size_t>(c)] = std::min(first[static_cast<std::size_t>(c)], i);
      last[static_cast<std::size_t>(c)] = std::max(last[static_cast<std::size_t>(c)], i);
    }
  }
}

}  // namespace

std::vector<cv::Mat1b> level_masks(const cv::Mat1b& mask, const std::vector<cv::Size>& sizes) {
  std::vector<cv::Mat1b> out(sizes.size());
  if (sizes.empty()) return out;
  out[0] = mask;
  const cv::Rect box = cv::boundingRect(mask);
  // The mask's runs, row by row (rows of the box; empty rows have none).
  std::vector<std::vector<std::pair<int, int>>> runs(static_cast<std::size_t>(box.height));
  for (int y = box.y; y < box.y + box.height; ++y) {
    row_runs(mask.ptr<uchar>(y), box.x, box.x + box.width, runs[static_cast<std::size_t>(y - box.y)]);
  }
  std::vector<int> x_first, x_last, y_first, y_last;
  for (std::size_t l = 1; l < sizes.size(); ++l) {
    const cv::Size size = sizes[l];
    if (size.width <= 0 || size.height <= 0) continue;
    out[l] = cv::Mat1b(size, uchar{0});
    if (box.empty()) continue;
    const double sx = static_cast<double>(mask.cols) / size.width, sy = static_cast<double>(mask.rows) / size.height;
    footprint_ranges(size.width, mask.cols, sx, x_first, x_last);
    footprint_ranges(size.height, mask.rows, sy, y_first, y_last);
    // Each run marks the level pixels whose footprint it meets.
    for (int y = box.y; y < box.y + box.height; ++y) {
      const auto& row = runs[static_cast<std::size_t>(y - box.y)];
      if (row.empty()) continue;
      for (int yl = y_first[static_cast<std::size_t>(y)]; yl <= y_last[static_cast<std::size_t>(y)]; ++yl) {
        uchar* o = out[l].ptr<uchar>(yl);
        for (const auto& [a, b] : row) {
          const int x0 = x_first[static_cast<std::size_t>(a)], x1 = x_last[static_cast<std::size_t>(b - 1)];
          std::memset(o + x0, 255, static_cast<std::size_t>(x1 - x0 + 1));
        }
      }
    }
  }
  return out;
}

}  // namespace stillslam
