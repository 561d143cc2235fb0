#include "stillslam/segmentation/segmentation_stage.h"

#include <spdlog/spdlog.h>

#include "stillslam/core/error.h"
#include "stillslam/core/thread_priority.h"

namespace stillslam {

SegmentationStage::SegmentationStage(DynamicMaskMaker maker, bool threaded, int thread_nice)
    : maker_(std::move(maker)), threaded_(threaded), thread_nice_(thread_nice) {
  if (threaded_) thread_ = std::thread([this] { run(); });
}

SegmentationStage::~SegmentationStage() { stop(); }

void SegmentationStage::stop() {
  {
    std::lock_guard lock(mutex_);
    stopped_ = true;
  }
  mailbox_.stop();
  done_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void SegmentationStage::submit(cv::Mat bgr, std::size_t frame_index) {
  {
    std::lock_guard lock(mutex_);
    if (stopped_) throw Error("segmentation stage is stopped");
    last_submitted_ = frame_index;
    ++submitted_;
  }
  if (threaded_) {
    mailbox_.put(Request{std::move(bgr), frame_index});
  } else {
    segment(Request{std::move(bgr), frame_index});
    latest();  // the segmenter's error, at once
  }
}

void SegmentationStage::run() {
  if (const std::string failed = lower_this_thread_priority(thread_nice_); !failed.empty()) {
    spdlog::warn("Segmentation.threadNice {}: the segmentation thread keeps its priority ({})", thread_nice_, failed);
  }
  while (std::optional<Request> request = mailbox_.take()) segment(*request);
}

void SegmentationStage::segment(const Request& request) {
  std::shared_ptr<const SegmentationResult> result;
  std::exception_ptr error;
  try {
    result = std::make_shared<const SegmentationResult>(maker_.make(request.image, request.frame_index));
  } catch (...) {
    error = std::current_exception();
  }
  {
    std::lock_guard lock(mutex_);
    if (result) latest_ = std::move(result);
    if (error && !error_) error_ = error;
  }
  done_.notify_all();
}

std::shared_ptr<const SegmentationResult> SegmentationStage::latest() const {
  std::lock_guard lock(mutex_);
  if (error_) std::rethrow_exception(error_);
  return latest_;
}

std::shared_ptr<const SegmentationResult> SegmentationStage::wait_for(std::size_t frame_index) const {
  std::unique_lock lock(mutex_);
  done_.wait(lock, [&] { return error_ || stopped_ || (latest_ && latest_->frame_index >= frame_index); });
  if (error_) std::rethrow_exception(error_);
  if (!latest_ || latest_->frame_index < frame_index) {
    throw Error("segmentation stage stopped before frame " + std::to_string(frame_index) + " was segmented");
  }
  return latest_;
}

bool SegmentationStage::busy() const {
  std::lock_guard lock(mutex_);
  return last_submitted_ && (!latest_ || latest_->frame_index < *last_submitted_) && !error_;
}

std::optional<std::size_t> SegmentationStage::last_submitted() const {
  std::lock_guard lock(mutex_);
  return last_submitted_;
}

std::size_t SegmentationStage::submitted() const {
  std::lock_guard lock(mutex_);
  return submitted_;
}

std::size_t SegmentationStage::skipped() const { return mailbox_.skipped(); }

}  // namespace stillslam
