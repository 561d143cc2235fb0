#pragma once
// Segmenter + dynamic classes + dilation + MaskHold: one frame's image in,
// its SegmentationResult out. Used by one thread at a time (the synchronous
// worker's or the asynchronous stage's); MaskHold needs the frames in order.
#include <memory>
#include <vector>

#include "stillslam/segmentation/mask_hold.h"
#include "stillslam/segmentation/segmentation_result.h"
#include "stillslam/segmentation/segmenter.h"

namespace stillslam {

class DynamicMaskMaker {
 public:
  // Throws Error when `segmenter` is null.
  DynamicMaskMaker(std::unique_ptr<Segmenter> segmenter, std::vector<int> dynamic_class_ids, int dilation_px,
                   MaskHoldOptions hold = {});

  SegmentationResult make(const cv::Mat& bgr, std::size_t frame_index);

 private:
  std::unique_ptr<Segmenter> segmenter_;
  std::vector<int> dynamic_class_ids_;
  int dilation_px_;
  MaskHold hold_;
};

}  // namespace stillslam
