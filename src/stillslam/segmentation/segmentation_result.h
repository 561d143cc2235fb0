#pragma once
#include <opencv2/core.hpp>

#include <cstddef>
#include <vector>

#include "stillslam/segmentation/detection.h"

namespace stillslam {

// One segmented frame, turned into what the frame builder filters with.
struct SegmentationResult {
  std::size_t frame_index = 0;  // the input frame that was segmented (SensorFrame::index)
  std::vector<Detection> detections;
  std::vector<cv::Mat1b> instances;  // frame-size masks of the dynamic-class detections
  cv::Mat1b dynamic_mask;  // frame-size union of the dynamic classes, dilated
  double coverage = 0;     // fraction of frame pixels in dynamic_mask
  // Fraction of frame pixels held over from instances lost since earlier
  // frames (MaskHold; included in dynamic_mask).
  double held_coverage = 0;
  cv::Mat1b held_mask;  // union of those held-over instances (empty: none)
  std::vector<cv::Mat1b> held_instances;  // each of them, frame-size (grown as MaskHold holds them)
  double time_ms = 0;      // segment() + mask building, on the segmenting thread
  double cpu_ms = 0;       // CPU time of that thread for it
};

}  // namespace stillslam
