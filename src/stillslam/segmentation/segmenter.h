#pragma once
#include <opencv2/core.hpp>

#include <cstddef>
#include <vector>

#include "stillslam/segmentation/detection.h"

namespace stillslam {

// Instance segmentation of one frame. Implementations are not required to be
// thread-safe; use one instance per thread (SegmentationWorker owns one).
class Segmenter {
 public:
  virtual ~Segmenter() = default;
  // bgr: 8UC3 BGR (8UC1 gray is replicated to three channels, 8UC4 BGRA drops
  // alpha). Any other type or an empty image throws stillslam::Error.
  virtual std::vector<Detection> segment(const cv::Mat& bgr) = 0;
  // The same for the input's frame `frame_index` (dataset order). Segmenters
  // that read precomputed masks (bench's oracle) need the index because the
  // asynchronous stage skips frames; a model ignores it.
  virtual std::vector<Detection> segment_frame(const cv::Mat& bgr, std::size_t frame_index) {
    (void)frame_index;
    return segment(bgr);
  }
};

}  // namespace stillslam
