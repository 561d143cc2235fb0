#include "stillslam/features/feature_grid.h"

#include <algorithm>
#include <cmath>

#include "stillslam/core/error.h"

namespace stillslam {

FeatureGrid::FeatureGrid(const std::vector<cv::KeyPoint>& undistorted, cv::Rect2f bounds, int cols,
                         int rows)
    : keypoints_(undistorted), bounds_(bounds), cols_(cols), rows_(rows) {
  if (cols < 1 || rows < 1 || !(bounds.width > 0) || !(bounds.height > 0)) {
    throw Error("FeatureGrid needs positive bounds and at least one cell per axis");
  }
  inv_cell_w_ = static_cast<float>(cols_) / bounds_.width;
  inv_cell_h_ = static_cast<float>(rows_) / bounds_.height;
  cells_.resize(static_cast<std::size_t>(cols_ * rows_));
  for (std::size_t i = 0; i < keypoints_.size(); ++i) {
    int c = 0, r = 0;
    if (cell_of(keypoints_[i].pt, &c, &r)) cells_[static_cast<std::size_t>(r * cols_ + c)].push_back(i);
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
  for (int row = r0; row <= r1; ++row) {
    for (int col = c0; col <= c1; ++col) {
      for (std::size_t i : cells_[static_cast<std::size_t>(row * cols_ + col)]) {
        const cv::KeyPoint& kp = keypoints_[i];
        if (min_level >= 0 && kp.octave < min_level) continue;
        if (max_level >= 0 && kp.octave > max_level) continue;
        if (std::abs(kp.pt.x - x) < r && std::abs(kp.pt.y - y) < r) found.push_back(i);
      }
    }
  }
  std::sort(found.begin(), found.end());
  return found;
}

}  // namespace stillslam
