#pragma once
// FAST corners of one pyramid level, detected cell by cell so that every
// textured region contributes: each cell first uses the initial threshold and
// falls back to the lower one when it found nothing (ORB-SLAM's iniThFAST /
// minThFAST).
#include <opencv2/core.hpp>
#include <vector>

namespace stillslam {

struct FastCellOptions {
  int cell_size = 30;
  int ini_threshold = 20;
  int min_threshold = 7;
  // Corners are kept only with this distance to the image border, so the
  // orientation disc and the rotated BRIEF pattern (radius 15) fit.
  int border = 16;
};

// Corners in `image` (CV_8UC1) coordinates, within [border, size - border):
// all corners at the initial threshold, then the low-threshold corners of
// each cell that had none. Deterministic order; no duplicates.
std::vector<cv::KeyPoint> detect_fast_in_cells(const cv::Mat& image, const FastCellOptions& options);

}  // namespace stillslam
