#pragma once
// Uniform grid over the (undistorted) image bounds for fast "keypoints near
// (x, y)" queries, as used by guided matching in tracking, fusion and
// triangulation. The cells are stored flat, row-major, each cell's keypoints
// (position, octave, index) contiguous, so one query reads one contiguous run
// per grid row instead of chasing a vector per cell and the keypoint array.
#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace stillslam {

class FeatureGrid {
 public:
  // Keypoints outside `bounds` are not indexed (they are never returned).
  FeatureGrid(const std::vector<cv::KeyPoint>& undistorted, cv::Rect2f bounds,
              int cols = 64, int rows = 48);

  // Indices of keypoints with |x_i - x| < r and |y_i - y| < r (a square
  // window, as ORB-SLAM) whose octave lies in [min_level, max_level]; a
  // negative min_level/max_level disables that bound. Sorted ascending.
  std::vector<std::size_t> features_in_area(float x, float y, float r, int min_level = -1,
                                            int max_level = -1) const;

  // Grid cell of a point, false if outside the bounds.
  bool cell_of(const cv::Point2f& p, int* col, int* row) const;
  int cols() const { return cols_; }
  int rows() const { return rows_; }
  const cv::Rect2f& bounds() const { return bounds_; }

 private:
  struct Entry {
    float x, y;
    int octave;
    std::uint32_t index;
  };
  cv::Rect2f bounds_;
  int cols_, rows_;
  float inv_cell_w_, inv_cell_h_;
  // Cell k (row-major) holds entries_[cell_start_[k] .. cell_start_[k + 1]),
  // by ascending keypoint index.
  std::vector<std::uint32_t> cell_start_;
  std::vector<Entry> entries_;
};

}  // namespace stillslam
