#include "stillslam/system/snapshot_instances.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace stillslam {

namespace {

// Largest external contour of the mask inside the box (only the box is
// scanned, so the cost follows the object's size, not the frame's).
std::vector<cv::Point> largest_outline(const cv::Mat1b& mask, const cv::Rect& box) {
  const cv::Rect roi = box & cv::Rect(0, 0, mask.cols, mask.rows);
  if (roi.empty()) return {};
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask(roi), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE, roi.tl());
  if (contours.empty()) return {};
  const auto largest = std::max_element(contours.begin(), contours.end(), [](const auto& a, const auto& b) {
    return cv::contourArea(a) < cv::contourArea(b);
  });
  return std::move(*largest);
}

}  // namespace

std::vector<FrameSnapshot::Instance> snapshot_instances(const std::vector<Detection>& detections,
                                                        const std::vector<int>& dynamic_class_ids) {
  std::vector<FrameSnapshot::Instance> out;
  out.reserve(detections.size());
  for (const Detection& d : detections) {
    FrameSnapshot::Instance instance;
    instance.class_name = d.class_name;
    instance.class_id = d.class_id;
    instance.score = d.score;
    // Whole pixels covering the box.
    const int x0 = static_cast<int>(std::floor(d.box.x)), y0 = static_cast<int>(std::floor(d.box.y));
    const int x1 = static_cast<int>(std::ceil(d.box.x + d.box.width));
    const int y1 = static_cast<int>(std::ceil(d.box.y + d.box.height));
    instance.box = cv::Rect(x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0));
    if (!d.mask.empty()) instance.outline = largest_outline(d.mask, instance.box);
    instance.dynamic =
        std::find(dynamic_class_ids.begin(), dynamic_class_ids.end(), d.class_id) != dynamic_class_ids.end();
    out.push_back(std::move(instance));
  }
  return out;
}

}  // namespace stillslam
