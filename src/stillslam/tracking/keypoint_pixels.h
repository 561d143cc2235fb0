#pragma once
// A frame's keypoints where they lie in the image (Frame::keypoints_raw,
// before undistortion): where a segmentation mask is looked up for each.
#include <opencv2/core.hpp>

#include <vector>

#include "stillslam/map/frame.h"

namespace stillslam {

std::vector<cv::Point2f> keypoint_pixels(const Frame& frame);

}  // namespace stillslam
