#pragma once
// An exclusion mask at each pyramid level's size: a level pixel is excluded
// when its footprint in the full-resolution mask, [x*sx, (x+1)*sx) x
// [y*sy, (y+1)*sy) with sx = full width / level width (sy likewise), holds
// any non-zero pixel. Made from the runs of non-zero pixels in each row of
// the mask, each marking the level pixels whose footprint it meets, so the
// cost follows the mask's outline, not its area (resizing the full mask with
// INTER_AREA keeps a subset of these pixels and costs several times more).
#include <opencv2/core.hpp>

#include <vector>

namespace stillslam {

// sizes[0] must be the mask's size (level 0 is the mask itself, not copied).
std::vector<cv::Mat1b> level_masks(const cv::Mat1b& mask, const std::vector<cv::Size>& sizes);

}  // namespace stillslam
