#include "stillslam/segmentation/segmentation_worker.h"

#include "stillslam/core/error.h"

namespace stillslam {

SegmentationWorker::SegmentationWorker(std::unique_ptr<Segmenter> segmenter, std::vector<int> dynamic_class_ids,
                                       int dilation_px, MaskHoldOptions hold)
    : maker_(std::move(segmenter), std::move(dynamic_class_ids), dilation_px, hold),
      worker_(WorkerMode::Threaded, [this](Job& job) { run(job); }) {}

SegmentationWorker::~SegmentationWorker() { stop(); }

std::future<SegmentationResult> SegmentationWorker::submit(cv::Mat bgr, std::size_t frame_index) {
  std::promise<SegmentationResult> promise;
  auto future = promise.get_future();
  if (stopped_) {
    promise.set_exception(std::make_exception_ptr(Error("segmentation worker is stopped")));
    return future;
  }
  worker_.submit(Job{std::move(bgr), frame_index, std::move(promise)});
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
    job.promise.set_value(maker_.make(job.image, job.frame_index));
  } catch (...) {
    job.promise.set_exception(std::current_exception());
  }
}

}  // namespace stillslam
