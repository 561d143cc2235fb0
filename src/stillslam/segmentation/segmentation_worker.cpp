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
      thread_([this] { run(); }) {
  if (!segmenter_) {
    stop();
    throw Error("SegmentationWorker needs a segmenter");
  }
}

SegmentationWorker::~SegmentationWorker() { stop(); }

std::future<SegmentationResult> SegmentationWorker::submit(cv::Mat bgr) {
  Job job{std::move(bgr), {}};
  auto future = job.promise.get_future();
  {
    std::lock_guard lock(mutex_);
    if (stopping_) {
      job.promise.set_exception(std::make_exception_ptr(Error("segmentation worker is stopped")));
      return future;
    }
    queue_.push_back(std::move(job));
  }
  wake_.notify_one();
  return future;
}

void SegmentationWorker::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  // Whatever the thread did not start.
  std::lock_guard lock(mutex_);
  for (auto& job : queue_)
    job.promise.set_exception(std::make_exception_ptr(Error("segmentation worker stopped before this frame")));
  queue_.clear();
}

void SegmentationWorker::run() {
  for (;;) {
    Job job;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      job = std::move(queue_.front());
      queue_.pop_front();
    }
    try {
      job.promise.set_value(process(job.image));
    } catch (...) {
      job.promise.set_exception(std::current_exception());
    }
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
