#include "stillslam/features/feature_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stillslam/core/error.h"

namespace stillslam {

FeatureGrid::FeatureGrid(const std::vector<cv::KeyPoint>& undistorted, cv::Rect2f bounds, int cols,
                         int rows)
    : bounds_(bounds), cols_(cols), rows_(rows) {
  if (cols < 1 || rows < 1 || !(bounds.width > 0) || !(bounds.height > 0)) {
    throw Error("FeatureGrid needs positive bounds and at least one cell per axis");
  }
  if (undistorted.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw Error("FeatureGrid holds at most 2^32 - 1 keypoints");
  }
  inv_cell_w_ = static_cast<float>(cols_) / bounds_.width;
  inv_cell_h_ = static_cast<float>(rows_) / bounds_.height;
  // Counting sort by cell: counts, prefix sums, then a stable fill.
  const std::size_t n_cells = static_cast<std::size_t>(cols_) * static_cast<std::size_t>(rows_);
  std::vector<int> cell_of_keypoint(undistorted.size(), -1);
  cell_start_.assign(n_cells + 1, 0);
  for (std::size_t i = 0; i < undistorted.size(); ++i) {
    int c = 0, r = 0;
    if (!cell_of(undistorted[i].pt, &c, &r)) continue;
    cell_of_keypoint[i] = r * cols_ + c;
    ++cell_start_[static_cast<std::size_t>(cell_of_keypoint[i]) + 1];
  }
  for (std::size_t k = 0; k < n_cells; ++k) cell_start_[k + 1] += cell_start_[k];
  entries_.resize(cell_start_[n_cells]);
  std::vector<std::uint32_t> next(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < undistorted.size(); ++i) {
    if (cell_of_keypoint[i] < 0) continue;
    const cv::KeyPoint& kp = undistorted[i];
    entries_[next[static_cast<std::size_t>(cell_of_keypoint[i])]++] =
        Entry{kp.pt.x, kp.pt.y, kp.octave, static_cast<std::uint32_t>(i)};
  }
}

bool FeatureGrid::cell_of(const cv::Point2f& p, int* col, int* row) const {
  const float fx = (p.x - bounds_.x) * inv_cell_w_;
  const float fy = (p.y - bounds_.y) * inv_cell_h_;
  if (!(fx >= 0.f && fy >= 0.f)) return false;  // also rejects NaN
  const int c = static_cast<int>(fx), r = static_cast<int>(fy);
  if (c >= cols_ || r >= rows_) return false;
  *col = c;
  *row = r;
  return true;
}

std::vector<std::size_t> FeatureGrid::features_in_area(float x, float y, float r, int min_level,
                                                       int max_level) const {
  std::vector<std::size_t> found;
  if (!(r > 0.f)) return found;
  // Cells touched by the open square (x - r, x + r) x (y - r, y + r).
  const int c0 = std::max(0, static_cast<int>(std::floor((x - r - bounds_.x) * inv_cell_w_)));
  const int c1 = std::min(cols_ - 1, static_cast<int>(std::floor((x + r - bounds_.x) * inv_cell_w_)));
  const int r0 = std::max(0, static_cast<int>(std::floor((y - r - bounds_.y) * inv_cell_h_)));
  const int r1 = std::min(rows_ - 1, static_cast<int>(std::floor((y + r - bounds_.y) * inv_cell_h_)));
  if (c0 > c1) return found;
  for (int row = r0; row <= r1; ++row) {
    // The cells c0..c1 of one row are contiguous in entries_.
    const std::size_t first = static_cast<std::size_t>(row) * static_cast<std::size_t>(cols_);
    const Entry* it = entries_.data() + cell_start_[first + static_cast<std::size_t>(c0)];
    const Entry* end = entries_.data() + cell_start_[first + static_cast<std::size_t>(c1) + 1];
    for (; it != end; ++it) {
      if (min_level >= 0 && it->octave < min_level) continue;
      if (max_level >= 0 && it->octave > max_level) continue;
      if (std::abs(it->x - x) < r && std::abs(it->y - y) < r) found.push_back(it->index);
    }
  }
  std::sort(found.begin(), found.end());
  return found;
}

}  // namespace stillslam
