#include "stillslam/segmentation/segmentation_options.h"

#include "stillslam/core/option_check.h"

namespace stillslam {

void SegmentationOptions::check() const {
  using namespace option_check;
  if (classes.empty()) throw OptionError("SegmentationOptions.classes", "empty", "must name at least one class");
  in_range("SegmentationOptions.score_threshold", score_threshold, 0, 1);
  in_half_open("SegmentationOptions.nms_iou_threshold", nms_iou_threshold, 0, 1);
  in_open("SegmentationOptions.mask_threshold", mask_threshold, 0, 1);
  at_least("SegmentationOptions.mask_dilation", mask_dilation, 0);
  at_least("SegmentationOptions.hold_frames", hold_frames, 0);
  at_least("SegmentationOptions.threads", threads, 0);
}

}  // namespace stillslam
