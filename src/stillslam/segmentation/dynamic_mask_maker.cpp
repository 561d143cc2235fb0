#include "stillslam/segmentation/dynamic_mask_maker.h"

#include "stillslam/core/error.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/core/thread_cpu_stopwatch.h"
#include "stillslam/segmentation/dynamic_mask.h"

namespace stillslam {

DynamicMaskMaker::DynamicMaskMaker(std::unique_ptr<Segmenter> segmenter, std::vector<int> dynamic_class_ids,
                                   int dilation_px, MaskHoldOptions hold)
    : segmenter_(std::move(segmenter)),
      dynamic_class_ids_(std::move(dynamic_class_ids)),
      dilation_px_(dilation_px),
      hold_(hold) {
  if (!segmenter_) throw Error("DynamicMaskMaker needs a segmenter");
}

SegmentationResult DynamicMaskMaker::make(const cv::Mat& bgr, std::size_t frame_index) {
  Stopwatch watch;
  ThreadCpuStopwatch cpu;
  SegmentationResult r;
  r.frame_index = frame_index;
  r.detections = segmenter_->segment_frame(bgr, frame_index);
  r.instances = dynamic_instances(r.detections, dynamic_class_ids_, bgr.size());
  r.dynamic_mask = dynamic_mask(r.instances, bgr.size(), dilation_px_);
  r.held_instances = hold_.update(r.instances, bgr.size(), frame_index);
  if (!r.held_instances.empty()) {
    r.held_mask = cv::Mat1b(bgr.size(), uchar{0});
    for (const cv::Mat1b& h : r.held_instances) cv::bitwise_or(r.held_mask, h, r.held_mask);
    r.held_coverage = mask_coverage(r.held_mask);
    cv::bitwise_or(r.dynamic_mask, r.held_mask, r.dynamic_mask);
  }
  r.coverage = mask_coverage(r.dynamic_mask);
  r.time_ms = watch.elapsed_ms();
  r.cpu_ms = cpu.elapsed_ms();
  return r;
}

}  // namespace stillslam
