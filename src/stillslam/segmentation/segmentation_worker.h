#pragma once
#include <opencv2/core.hpp>

#include <atomic>
#include <future>
#include <memory>
#include <vector>

#include "stillslam/core/worker.h"
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

// Runs a Segmenter on its own thread (a core/worker.h stage): submit() returns
// at once and the future delivers the result (or the Error the segmenter
// threw). Frames are processed in submission order, which MaskHold relies on.
// The caller can do other work meanwhile (stereo: the right image's ORB); the
// left image's extraction needs the mask, so it waits for the future.
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
  void run(Job& job);
  SegmentationResult process(const cv::Mat& image);

  std::unique_ptr<Segmenter> segmenter_;
  std::vector<int> dynamic_class_ids_;
  int dilation_px_;
  MaskHold hold_;  // used on the worker thread only
  std::atomic<bool> stopped_{false};
  Worker<Job> worker_;  // last: its thread starts after the members above exist
};

}  // namespace stillslam
