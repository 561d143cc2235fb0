#include "stillslam/features/fast_cells.h"

#include <algorithm>
#include <opencv2/features2d.hpp>

namespace stillslam {

std::vector<cv::KeyPoint> detect_fast_in_cells(const cv::Mat& image, const FastCellOptions& options) {
  // cv::FAST never reports corners within 3 px of the image it is given, so
  // every cell's ROI is grown by 3 px on each side: interiors tile the region
  // exactly and neighbouring cells cannot report the same pixel.
  constexpr int kFastMargin = 3;
  std::vector<cv::KeyPoint> corners;
  const int min_x = options.border - kFastMargin, min_y = options.border - kFastMargin;
  const int max_x = image.cols - options.border + kFastMargin;
  const int max_y = image.rows - options.border + kFastMargin;
  const int width = max_x - min_x - 2 * kFastMargin;   // interior extent
  const int height = max_y - min_y - 2 * kFastMargin;
  if (width <= 0 || height <= 0) return corners;

  const int n_cols = std::max(1, width / options.cell_size);
  const int n_rows = std::max(1, height / options.cell_size);
  const int cell_w = (width + n_cols - 1) / n_cols;
  const int cell_h = (height + n_rows - 1) / n_rows;

  std::vector<cv::KeyPoint> cell_corners;
  for (int r = 0; r < n_rows; ++r) {
    const int y0 = min_y + r * cell_h;
    const int y1 = std::min(y0 + cell_h + 2 * kFastMargin, max_y);
    if (y1 - y0 <= 2 * kFastMargin) continue;
    for (int c = 0; c < n_cols; ++c) {
      const int x0 = min_x + c * cell_w;
      const int x1 = std::min(x0 + cell_w + 2 * kFastMargin, max_x);
      if (x1 - x0 <= 2 * kFastMargin) continue;
      const cv::Mat cell = image(cv::Range(y0, y1), cv::Range(x0, x1));
      cell_corners.clear();
      cv::FAST(cell, cell_corners, options.ini_threshold, true);
      if (cell_corners.empty() && options.min_threshold < options.ini_threshold) {
        cv::FAST(cell, cell_corners, options.min_threshold, true);
      }
      for (auto& kp : cell_corners) {
        kp.pt.x += static_cast<float>(x0);
        kp.pt.y += static_cast<float>(y0);
        corners.push_back(kp);
      }
    }
  }
  return corners;
}

}  // namespace stillslam
