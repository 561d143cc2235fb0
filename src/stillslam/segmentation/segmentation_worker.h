#pragma once
#include <opencv2/core.hpp>

#include <condition_variable>
#include <deque>
#include <future>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "stillslam/segmentation/detection.h"
#include "stillslam/segmentation/mask_hold.h"
#include "stillslam/segmentation/segmenter.h"

namespace stillslam {

struct SegmentationResult {
  std::vector<Detection> detections;
  cv::Mat1b dynamic_mask;  // frame-size union of the dynamic classes, dilated
  double coverage = 0;     // fraction of frame pixels in dynamic_mask
  // Fraction of frame pixels held over from instances lost since earlier
  // frames (MaskHold; included in dynamic_mask).
  double held_coverage = 0;
  double time_ms = 0;      // segment() + mask building, on the worker thread
};

// Runs a Segmenter on its own thread so that frame k is segmented while the
// caller extracts ORB features of frame k: submit() returns at once and the
// future delivers the result (or the Error the segmenter threw). Frames are
// processed in submission order, which MaskHold relies on.
class SegmentationWorker {
 public:
  SegmentationWorker(std::unique_ptr<Segmenter> segmenter, std::vector<int> dynamic_class_ids, int dilation_px,
                     MaskHoldOptions hold = {});
  ~SegmentationWorker();  // stop() + join
  SegmentationWorker(const SegmentationWorker&) = delete;
  SegmentationWorker& operator=(const SegmentationWorker&) = delete;

  // The image is shared, not copied: don't write into it until the future is ready.
  std::future<SegmentationResult> submit(cv::Mat bgr);

  // Finishes the frame in progress; frames still queued get an Error in their
  // future, and later submit() calls too. Idempotent.
  void stop();

 private:
  struct Job {
    cv::Mat image;
    std::promise<SegmentationResult> promise;
  };
  void run();
  SegmentationResult process(const cv::Mat& image);

  std::unique_ptr<Segmenter> segmenter_;
  std::vector<int> dynamic_class_ids_;
  int dilation_px_;
  MaskHold hold_;  // used on the worker thread only
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Job> queue_;
  bool stopping_ = false;
  std::thread thread_;  // last: starts after the members above exist
};

}  // namespace stillslam
