#pragma once
#include <opencv2/core.hpp>

namespace stillslam {

// Every pixel within Euclidean distance radius_px of a set pixel (the same
// result as dynamic_mask's disc dilation), computed on the mask's bounding box
// grown by the radius only: a disc dilation for small radii, an exact distance
// transform for large ones (cheaper there). radius_px <= 0 returns a copy.
cv::Mat1b grow_mask(const cv::Mat1b& mask, int radius_px);

}  // namespace stillslam
