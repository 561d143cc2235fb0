#pragma once
// An exclusion mask at each pyramid level's size: a level pixel is excluded
// when its footprint in the full-resolution mask, [x*sx, (x+1)*sx) x
// [y*sy, (y+1)*sy) with sx = full width / level width (sy likewise), holds
// any non-zero pixel. From one integral image of the mask's bounding box:
// 1.75 ms for seven levels of a 640x480 mask with two people, where resizing
// the full mask with INTER_AREA (whose > 0 pixels are a subset of these) took
// 5.8 ms (one thread, 2026-12-02).
#include <opencv2/core.hpp>

#include <vector>

namespace stillslam {

// sizes[0] must be the mask's size (level 0 is the mask itself, not copied).
std::vector<cv::Mat1b> level_masks(const cv::Mat1b& mask, const std::vector<cv::Size>& sizes);

}  // namespace stillslam
