#include "stillslam/segmentation/mask_hold.h"

#include <opencv2/imgproc.hpp>

#include "stillslam/core/option_check.h"

namespace stillslam {

cv::Mat1b MaskHold::update(const std::vector<cv::Mat1b>& instances, cv::Size size) {
  if (options_.frames <= 0) return {};
  cv::Mat1b found(size, uchar{0});
  for (const cv::Mat1b& m : instances) {
    if (m.size() == size) cv::bitwise_or(found, m, found);
  }
  std::vector<Held> next;
  cv::Mat1b held_union;
  const cv::Mat grow = options_.grow_px_per_frame > 0
                           ? cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * options_.grow_px_per_frame + 1,
                                                                                   2 * options_.grow_px_per_frame + 1))
                           : cv::Mat();
  for (Held& h : held_) {
    if (h.mask.size() != size || h.age + 1 > options_.frames) continue;
    const int area = cv::countNonZero(h.mask);
    cv::Mat1b overlap;
    cv::bitwise_and(h.mask, found, overlap);
    if (area == 0 || cv::countNonZero(overlap) >= options_.min_overlap * area) continue;  // found again
    ++h.age;
    if (!grow.empty()) cv::dilate(h.mask, h.mask, grow);
    if (held_union.empty()) held_union = cv::Mat1b(size, uchar{0});
    cv::bitwise_or(held_union, h.mask, held_union);
    next.push_back(std::move(h));
  }
  for (const cv::Mat1b& m : instances) {
    if (m.size() == size && cv::countNonZero(m) > 0) next.push_back({m.clone(), 0});
  }
  held_ = std::move(next);
  return held_union;
}

void MaskHoldOptions::check() const {
  using namespace option_check;
  at_least("MaskHoldOptions.frames", frames, 0);
  in_half_open("MaskHoldOptions.min_overlap", min_overlap, 0, 1);
  at_least("MaskHoldOptions.grow_px_per_frame", grow_px_per_frame, 0);
}

}  // namespace stillslam
