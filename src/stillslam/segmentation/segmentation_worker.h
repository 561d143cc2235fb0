#pragma once
#include <opencv2/core.hpp>

#include <atomic>
#include <cstddef>
#include <future>
#include <memory>
#include <vector>

#include "stillslam/core/worker.h"
#include "stillslam/segmentation/dynamic_mask_maker.h"
#include "stillslam/segmentation/segmentation_result.h"

namespace stillslam {

// Runs a Segmenter on its own thread (a core/worker.h stage): submit() returns
// at once and the future delivers the result (or the Error the segmenter
// threw). Frames are processed in submission order, which MaskHold relies on.
// The caller can do other work meanwhile (stereo: the right image's ORB); the
// left image's extraction needs the mask, so it waits for the future.
// (Segmentation.mode sync; the asynchronous stage is segmentation_stage.h.)
class SegmentationWorker {
 public:
  SegmentationWorker(std::unique_ptr<Segmenter> segmenter, std::vector<int> dynamic_class_ids, int dilation_px,
                     MaskHoldOptions hold = {});
  ~SegmentationWorker();  // stop() + join
  SegmentationWorker(const SegmentationWorker&) = delete;
  SegmentationWorker& operator=(const SegmentationWorker&) = delete;

  // The image is shared, not copied: don't write into it until the future is
  // ready. frame_index: the input frame's index (SensorFrame::index).
  std::future<SegmentationResult> submit(cv::Mat bgr, std::size_t frame_index = 0);

  // Finishes the frame in progress; frames still queued get an Error in their
  // future, and later submit() calls too. Idempotent.
  void stop();

 private:
  struct Job {
    cv::Mat image;
    std::size_t frame_index = 0;
    std::promise<SegmentationResult> promise;
  };
  void run(Job& job);

  DynamicMaskMaker maker_;  // used on the worker thread only
  std::atomic<bool> stopped_{false};
  Worker<Job> worker_;  // last: its thread starts after the members above exist
};

}  // namespace stillslam
