#pragma once
// Steered BRIEF: the pattern is rotated by each keypoint's angle before the
// intensity tests, which makes the descriptor rotation invariant.
#include <opencv2/core.hpp>
#include <vector>

#include "stillslam/features/brief_pattern.h"

namespace stillslam {

// `smoothed`: CV_8UC1 level image after Gaussian smoothing; keypoints at
// integer positions, >= BriefPattern::kRadius from the border, angle in
// degrees. Writes rows [row_offset, row_offset + keypoints.size()) of
// `descriptors` (N x 32 CV_8U, allocated by the caller). Bit j of byte i is
// the test of pair 8i + j: 1 when I(p1) < I(p2).
void compute_brief(const cv::Mat& smoothed, const std::vector<cv::KeyPoint>& keypoints,
                   const BriefPattern& pattern, cv::Mat& descriptors, int row_offset = 0);

}  // namespace stillslam
