#include "stillslam/segmentation/dynamic_mask.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "stillslam/core/error.h"
#include "stillslam/segmentation/mask_grow.h"

namespace stillslam {

std::vector<cv::Mat1b> dynamic_instances(const std::vector<Detection>& detections,
                                         const std::vector<int>& dynamic_class_ids, cv::Size size) {
  std::vector<cv::Mat1b> out;
  const cv::Rect frame(0, 0, size.width, size.height);
  for (const auto& d : detections) {
    if (std::find(dynamic_class_ids.begin(), dynamic_class_ids.end(), d.class_id) == dynamic_class_ids.end())
      continue;
    if (!d.mask.empty()) {
      if (d.mask.size() != size)
        throw Error("dynamic_mask: detection mask is " + std::to_string(d.mask.cols) + "x" +
                    std::to_string(d.mask.rows) + " but the frame is " + std::to_string(size.width) + "x" +
                    std::to_string(size.height));
      out.push_back(d.mask);
    } else {
      const cv::Rect box = cv::Rect(cv::Point(cvFloor(d.box.x), cvFloor(d.box.y)),
                                    cv::Point(cvCeil(d.box.x + d.box.width), cvCeil(d.box.y + d.box.height))) &
                           frame;
      cv::Mat1b m(size, uchar{0});
      m(box).setTo(255);
      out.push_back(m);
    }
  }
  return out;
}

cv::Mat1b dynamic_mask(const std::vector<cv::Mat1b>& instances, cv::Size size, int dilation_px) {
  cv::Mat1b mask(size, uchar{0});
  for (const cv::Mat1b& m : instances) cv::bitwise_or(mask, m, mask);
  // A true disc (OpenCV's MORPH_ELLIPSE is not one): every pixel within dilation_px of the mask.
  if (dilation_px > 0) return grow_mask(mask, dilation_px);
  return mask;
}

cv::Mat1b dynamic_mask(const std::vector<Detection>& detections, const std::vector<int>& dynamic_class_ids,
                       cv::Size size, int dilation_px) {
  return dynamic_mask(dynamic_instances(detections, dynamic_class_ids, size), size, dilation_px);
}

std::vector<std::size_t> keypoints_outside_mask(const std::vector<cv::KeyPoint>& keypoints, const cv::Mat1b& mask) {
  std::vector<std::size_t> keep;
  keep.reserve(keypoints.size());
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    if (!mask.empty()) {
      const int x = static_cast<int>(std::lround(keypoints[i].pt.x));
      const int y = static_cast<int>(std::lround(keypoints[i].pt.y));
      if (x >= 0 && y >= 0 && x < mask.cols && y < mask.rows && mask(y, x) != 0) continue;
    }
    keep.push_back(i);
  }
  return keep;
}

double mask_coverage(const cv::Mat1b& mask) {
  if (mask.empty()) return 0.0;
  return static_cast<double>(cv::countNonZero(mask)) / static_cast<double>(mask.total());
}

}  // namespace stillslam
