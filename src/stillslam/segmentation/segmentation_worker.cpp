#include "stillslam/segmentation/segmentation_worker.h"

#include "stillslam/core/error.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/segmentation/dynamic_mask.h"

namespace stillslam {

SegmentationWorker::SegmentationWorker(std::unique_ptr<Segmenter> segmenter, std::vector<int> dynamic_class_ids,
                                       int dilation_px, MaskHoldOptions hold)
    : segmenter_(std::move(segmenter)),
      dynamic_class_ids_(std::move(dynamic_class_ids)),
      dilation_px_(dilation_px),
      hold_(hold),
      worker_(WorkerMode::Threaded, [this](Job& job) { run(job); }) {
  if (!segmenter_) {
    stop();
    throw Error("SegmentationWorker needs a segmenter");
  }
}

SegmentationWorker::~SegmentationWorker() { stop(); }

std::future<SegmentationResult> SegmentationWorker::submit(cv::Mat bgr) {
  std::promise<SegmentationResult> promise;
  auto future = promise.get_future();
  if (stopped_) {
    promise.set_exception(std::make_exception_ptr(Error("segmentation worker is stopped")));
    return future;
  }
  worker_.submit(Job{std::move(bgr), std::move(promise)});
  return future;
}

void SegmentationWorker::stop() {
  stopped_ = true;
  for (Job& job : worker_.cancel()) {
    job.promise.set_exception(std::make_exception_ptr(Error("segmentation worker stopped before this frame")));
  }
}

void SegmentationWorker::run(Job& job) {
  try {
    job.promise.set_value(process(job.image));
  } catch (...) {
    job.promise.set_exception(std::current_exception());
  }
}

SegmentationResult SegmentationWorker::process(const cv::Mat& image) {
  Stopwatch watch;
  SegmentationResult r;
  r.detections = segmenter_->segment(image);
  const std::vector<cv::Mat1b> instances = dynamic_instances(r.detections, dynamic_class_ids_, image.size());
  r.dynamic_mask = dynamic_mask(instances, image.size(), dilation_px_);
  const cv::Mat1b held = hold_.update(instances, image.size());
  if (!held.empty()) {
    r.held_coverage = mask_coverage(held);
    cv::bitwise_or(r.dynamic_mask, held, r.dynamic_mask);
  }
  r.coverage = mask_coverage(r.dynamic_mask);
  r.time_ms = watch.elapsed_ms();
  return r;
}

}  // namespace stillslam
