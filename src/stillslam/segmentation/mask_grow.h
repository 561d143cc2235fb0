#pragma once
#include <opencv2/core.hpp>

namespace stillslam {

// Every pixel within Euclidean distance radius_px of a set pixel: the same
// result as dynamic_mask's disc dilation (a pixel (dx, dy) away is reached
// when dx^2 + dy^2 <= radius_px^2), computed from the runs of set pixels in
// each row of the mask's bounding box. Set pixels come out as 255.
// radius_px <= 0 returns a copy.
cv::Mat1b grow_mask(const cv::Mat1b& mask, int radius_px);

}  // namespace stillslam
