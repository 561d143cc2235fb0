#pragma once
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>

#include <cstddef>
#include <vector>

#include "stillslam/segmentation/detection.h"

namespace stillslam {

// Union (255) of the masks of detections whose class is in dynamic_class_ids,
// grown by dilation_px pixels (every pixel within Euclidean distance dilation_px of
// a mask pixel) so that keypoints on the blurry border of a moving object go too.
// Detections without a mask contribute their box. Size must be the frame size.
cv::Mat1b dynamic_mask(const std::vector<Detection>& detections, const std::vector<int>& dynamic_class_ids,
                       cv::Size size, int dilation_px);

// The same in two steps: the frame-size mask of each detection of a dynamic
// class (its box when it has no mask), then their dilated union.
std::vector<cv::Mat1b> dynamic_instances(const std::vector<Detection>& detections,
                                         const std::vector<int>& dynamic_class_ids, cv::Size size);
cv::Mat1b dynamic_mask(const std::vector<cv::Mat1b>& instances, cv::Size size, int dilation_px);

// The keypoint filter used by the frame builder: indices (ascending) of the
// keypoints whose rounded pixel is outside the mask (mask == 0). Keypoints outside
// the image count as outside the mask. An empty mask keeps every keypoint.
std::vector<std::size_t> keypoints_outside_mask(const std::vector<cv::KeyPoint>& keypoints, const cv::Mat1b& mask);

// Fraction of mask pixels that are set (0 for an empty mask).
double mask_coverage(const cv::Mat1b& mask);

}  // namespace stillslam
