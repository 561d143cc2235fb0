#pragma once
// Asynchronous segmentation (Segmentation.mode async): a stage with its own
// thread, fed through a latest-value mailbox. A request the thread has not
// started when a newer one comes is skipped (counted): the segmenter always
// works on the newest frame it was given. Finished results go to a slot the
// frame builder reads without waiting (latest()); wait_for() is for the frames
// whose last mask got too old.
//
// Threaded, the stage's thread can run at a lower priority than the others
// (thread_nice: its nice value raised by this, core/thread_priority.h), so
// that on a busy machine tracking gets a core first and segmentation takes
// what is left; a failure to lower it is a warning.
//
// Not threaded (deterministic runs): submit() segments on the caller's
// thread at once, so results never depend on timing; the latency is then
// modelled by the reader (async_masks.h).
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "stillslam/core/mailbox.h"
#include "stillslam/segmentation/dynamic_mask_maker.h"

namespace stillslam {

class SegmentationStage {
 public:
  SegmentationStage(DynamicMaskMaker maker, bool threaded, int thread_nice = 0);
  ~SegmentationStage();  // stop() + join
  SegmentationStage(const SegmentationStage&) = delete;
  SegmentationStage& operator=(const SegmentationStage&) = delete;

  // Leaves the frame for the stage (the image is shared, not copied: don't
  // write into it). Replaces a request the stage has not started.
  void submit(cv::Mat bgr, std::size_t frame_index);

  // The newest finished result; null before the first. Throws the Error the
  // segmenter threw (the run must not go on without masks).
  std::shared_ptr<const SegmentationResult> latest() const;
  // Waits for a result of `frame_index` or a later frame, which must have
  // been submitted. Throws Error when the stage stopped or the segmenter failed.
  std::shared_ptr<const SegmentationResult> wait_for(std::size_t frame_index) const;

  // The newest request has no result yet (queued or being segmented).
  bool busy() const;
  // The newest submitted frame, if any.
  std::optional<std::size_t> last_submitted() const;
  std::size_t submitted() const;  // requests
  std::size_t skipped() const;    // requests replaced before the stage took them
  bool threaded() const { return threaded_; }

  // Finishes the frame in progress, drops a queued request. Idempotent.
  void stop();

 private:
  struct Request {
    cv::Mat image;
    std::size_t frame_index = 0;
  };
  void run();
  void segment(const Request& request);

  DynamicMaskMaker maker_;  // on the stage thread only (caller's when not threaded)
  const bool threaded_;
  const int thread_nice_;
  Mailbox<Request> mailbox_;
  mutable std::mutex mutex_;
  mutable std::condition_variable done_;
  std::shared_ptr<const SegmentationResult> latest_;
  std::exception_ptr error_;
  std::optional<std::size_t> last_submitted_;
  std::size_t submitted_ = 0;
  bool stopped_ = false;
  std::thread thread_;  // last: starts after the members above exist
};

}  // namespace stillslam
