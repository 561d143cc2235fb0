#include "stillslam/features/fast_cells.h"

#include <algorithm>
#include <opencv2/features2d.hpp>

namespace stillslam {

std::vector<cv::KeyPoint> detect_fast_in_cells(const cv::Mat& image, const FastCellOptions& options) {
  // cv::FAST never reports corners within 3 px of the image it is given, so
  // every ROI is grown by 3 px on each side of the area whose corners we want.
  constexpr int kFastMargin = 3;
  std::vector<cv::KeyPoint> corners;
  const int x0 = options.border, y0 = options.border;  // interior: [x0, x1) x [y0, y1)
  const int x1 = image.cols - options.border, y1 = image.rows - options.border;
  const int width = x1 - x0, height = y1 - y0;
  if (width <= 0 || height <= 0) return corners;

  const int n_cols = std::max(1, width / options.cell_size);
  const int n_rows = std::max(1, height / options.cell_size);
  const int cell_w = (width + n_cols - 1) / n_cols;
  const int cell_h = (height + n_rows - 1) / n_rows;

  // Common case first: one FAST pass with the initial threshold over the
  // whole interior (cheaper than one call per cell, and non-maximum
  // suppression is not cut at cell borders). Every cell that got nothing is
  // then searched again with the low threshold.
  const cv::Mat interior = image(cv::Range(y0 - kFastMargin, y1 + kFastMargin),
                                 cv::Range(x0 - kFastMargin, x1 + kFastMargin));
  cv::FAST(interior, corners, options.ini_threshold, true);
  std::vector<int> per_cell(static_cast<std::size_t>(n_cols * n_rows), 0);
  for (auto& kp : corners) {
    kp.pt.x += static_cast<float>(x0 - kFastMargin);
    kp.pt.y += static_cast<float>(y0 - kFastMargin);
    const int c = std::min(n_cols - 1, (static_cast<int>(kp.pt.x) - x0) / cell_w);
    const int r = std::min(n_rows - 1, (static_cast<int>(kp.pt.y) - y0) / cell_h);
    ++per_cell[static_cast<std::size_t>(r * n_cols + c)];
  }
  if (options.min_threshold >= options.ini_threshold) return corners;

  // Retry with the low threshold in cells that got nothing; horizontal runs
  // of empty cells share one cv::FAST call (fewer calls, and non-maximum
  // suppression is cut only at run ends).
  std::vector<cv::KeyPoint> low;
  for (int r = 0; r < n_rows; ++r) {
    const int cy0 = y0 + r * cell_h, cy1 = std::min(cy0 + cell_h, y1);
    if (cy1 <= cy0) continue;
    for (int c = 0; c < n_cols;) {
      if (per_cell[static_cast<std::size_t>(r * n_cols + c)] > 0) {
        ++c;
        continue;
      }
      int c_end = c + 1;
      while (c_end < n_cols && per_cell[static_cast<std::size_t>(r * n_cols + c_end)] == 0) ++c_end;
      const int cx0 = x0 + c * cell_w, cx1 = std::min(x0 + c_end * cell_w, x1);
      c = c_end;
      if (cx1 <= cx0) continue;
      const cv::Mat run = image(cv::Range(cy0 - kFastMargin, cy1 + kFastMargin),
                                cv::Range(cx0 - kFastMargin, cx1 + kFastMargin));
      low.clear();
      cv::FAST(run, low, options.min_threshold, true);
      for (auto& kp : low) {
        kp.pt.x += static_cast<float>(cx0 - kFastMargin);
        kp.pt.y += static_cast<float>(cy0 - kFastMargin);
        corners.push_back(kp);
      }
    }
  }
  return corners;
}

}  // namespace stillslam
