#pragma once
#include <opencv2/core.hpp>

#include <vector>

namespace stillslam {

// Class-aware non-maximum suppression: boxes only suppress boxes of the same
// class. OpenCV 4.6 has no cv::dnn::NMSBoxesBatched (added in 4.7), so this does
// what it does: shift each class's boxes to a disjoint region, then cv::dnn::NMSBoxes.
// Returns indices into boxes, highest score first.
std::vector<int> class_aware_nms(const std::vector<cv::Rect2d>& boxes, const std::vector<float>& scores,
                                 const std::vector<int>& class_ids, float score_threshold, float iou_threshold);

// Plain NMS over all boxes regardless of class (cv::dnn::NMSBoxes); highest score first.
std::vector<int> agnostic_nms(const std::vector<cv::Rect2d>& boxes, const std::vector<float>& scores,
                              float score_threshold, float iou_threshold);

}  // namespace stillslam
