#pragma once
// The dynamic mask of each frame in Segmentation.mode async, without waiting
// on ordinary frames. Per frame:
//   1. the scheduler (segmentation_scheduler.h) decides whether this frame
//      goes to the segmentation stage (segmentation_stage.h);
//   2. the newest usable result becomes the "fresh" one: threaded, any
//      finished result; deterministic, the result of frame k from frame
//      k + modelled_latency on (timing-independent);
//   3. the mask is the fresh result's if it is of this frame (age 0), else
//      that result carried to this frame (age = frames since it);
//   4. no result yet, or one older than max_mask_age: the frame waits for a
//      fresh mask (the one in flight if young enough, else its own).
#include <cstddef>
#include <deque>
#include <memory>

#include "stillslam/segmentation/segmentation_options.h"
#include "stillslam/segmentation/segmentation_scheduler.h"
#include "stillslam/segmentation/segmentation_stage.h"

namespace stillslam {

struct AsyncMaskOptions {
  int interval = 3;
  int max_mask_age = 15;
  int modelled_latency = 3;  // used when the stage is not threaded
  // Without mask propagation: a carried mask grows this much per frame of
  // age (as MaskHold grows held instances) to cover the people's motion.
  int grow_px_per_frame = 4;
  void check() const;
  static AsyncMaskOptions from(const SegmentationOptions& segmentation);
};

struct FrameMask {
  cv::Mat1b mask;  // frame size, 255: dynamic
  int age = 0;     // input frames since the segmented frame
  std::shared_ptr<const SegmentationResult> source;  // the segmentation it comes from
  ScheduleReason scheduled = ScheduleReason::None;  // this frame went to the stage, why
  bool waited = false;   // this frame waited for a fresh mask
  double wait_ms = 0;
};

class AsyncMasks {
 public:
  // `stage` is not owned and outlives this.
  AsyncMasks(SegmentationStage& stage, AsyncMaskOptions options);

  // bgr: the frame's colour image; frame_index: SensorFrame::index (increasing).
  FrameMask mask_for(const cv::Mat& bgr, std::size_t frame_index);

  // The next frame gets a segmentation slot if the stage is idle (a keyframe
  // candidate deferred for an old mask, weak tracking).
  void request_urgent() { scheduler_.request_urgent(); }

  std::size_t skipped() const { return stage_.skipped(); }
  std::size_t submitted() const { return stage_.submitted(); }

 private:
  bool stage_busy() const;
  void submit(const cv::Mat& bgr, std::size_t frame_index);
  // Moves the results usable at `frame_index` into fresh_.
  void collect(std::size_t frame_index);
  // Waits (threaded) or takes at once (deterministic) the result of `frame_index`.
  void wait_for(std::size_t frame_index);
  cv::Mat1b carried(const SegmentationResult& result, int age) const;

  SegmentationStage& stage_;
  AsyncMaskOptions options_;
  SegmentationScheduler scheduler_;
  std::shared_ptr<const SegmentationResult> fresh_;
  // Deterministic: results segmented but not usable yet (modelled latency).
  std::deque<std::shared_ptr<const SegmentationResult>> pending_;
};

}  // namespace stillslam
