#include "stillslam/segmentation/nms.h"

#include <opencv2/dnn.hpp>

#include <algorithm>

namespace stillslam {

std::vector<int> class_aware_nms(const std::vector<cv::Rect2d>& boxes, const std::vector<float>& scores,
                                 const std::vector<int>& class_ids, float score_threshold, float iou_threshold) {
  if (boxes.empty()) return {};
  double extent = 0;
  for (const auto& b : boxes) extent = std::max({extent, b.br().x, b.br().y});
  const double offset_step = extent + 1.0;
  std::vector<cv::Rect2d> shifted(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const double offset = offset_step * class_ids[i];
    shifted[i] = cv::Rect2d(boxes[i].x + offset, boxes[i].y + offset, boxes[i].width, boxes[i].height);
  }
  std::vector<int> keep;
  cv::dnn::NMSBoxes(shifted, scores, score_threshold, iou_threshold, keep);
  return keep;
}

std::vector<int> agnostic_nms(const std::vector<cv::Rect2d>& boxes, const std::vector<float>& scores,
                              float score_threshold, float iou_threshold) {
  std::vector<int> keep;
  if (!boxes.empty()) cv::dnn::NMSBoxes(boxes, scores, score_threshold, iou_threshold, keep);
  return keep;
}

}  // namespace stillslam
