#include "stillslam/segmentation/mask_hold.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>

#include "stillslam/core/option_check.h"

namespace stillslam {

std::vector<cv::Mat1b> MaskHold::update(const std::vector<cv::Mat1b>& instances, cv::Size size,
                                        std::size_t frame_index) {
  if (options_.frames <= 0) return {};
  const std::size_t step = frame_index > last_index_ ? frame_index - last_index_ : 0;
  last_index_ = frame_index;
  cv::Mat1b found(size, uchar{0});
  for (const cv::Mat1b& m : instances) {
    if (m.size() == size) cv::bitwise_or(found, m, found);
  }
  const int grow_px = static_cast<int>(std::min<std::size_t>(step * options_.grow_px_per_frame, 4096));
  const cv::Mat grow =
      grow_px > 0 ? cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * grow_px + 1, 2 * grow_px + 1)) : cv::Mat();
  std::vector<Held> next;
  std::vector<cv::Mat1b> held;
  for (Held& h : held_) {
    if (h.mask.size() != size || frame_index - h.detected > static_cast<std::size_t>(options_.frames)) continue;
    const int area = cv::countNonZero(h.mask);
    cv::Mat1b overlap;
    cv::bitwise_and(h.mask, found, overlap);
    if (area == 0 || cv::countNonZero(overlap) >= options_.min_overlap * area) continue;  // found again
    if (!grow.empty()) cv::dilate(h.mask, h.mask, grow);
    held.push_back(h.mask);
    next.push_back(std::move(h));
  }
  for (const cv::Mat1b& m : instances) {
    if (m.size() == size && cv::countNonZero(m) > 0) next.push_back({m.clone(), frame_index});
  }
  held_ = std::move(next);
  return held;
}

void MaskHoldOptions::check() const {
  using namespace option_check;
  at_least("MaskHoldOptions.frames", frames, 0);
  in_half_open("MaskHoldOptions.min_overlap", min_overlap, 0, 1);
  at_least("MaskHoldOptions.grow_px_per_frame", grow_px_per_frame, 0);
}

}  // namespace stillslam
