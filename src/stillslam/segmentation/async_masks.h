#pragma once
// The dynamic mask of each frame in Segmentation.mode async, without waiting
// on ordinary frames. Per frame:
//   1. the scheduler (segmentation_scheduler.h) decides whether this frame
//      goes to the segmentation stage (segmentation_stage.h);
//   2. the newest usable result becomes the "fresh" one: threaded, any
//      finished result; deterministic, the result of frame k from frame
//      k + modelled_latency on (timing-independent);
//   3. the mask is the fresh result's if it is of this frame (age 0), else
//      that result carried to this frame (age = processed frames since it,
//      so frames --realtime dropped do not age a mask): by the
//      MaskPropagator (mask_propagation.h: camera motion with depth, then
//      the instances' own optical flow) when there is one and the frame's
//      grey image is given, else grown grow_px_per_frame per input frame of
//      age, max_grow_px at most;
//   4. no result yet, or one older than max_mask_age: the frame waits for a
//      fresh mask (the one in flight if young enough, else its own).
#include <Eigen/Geometry>

#include <cstddef>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "stillslam/segmentation/mask_propagation.h"
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
  int max_grow_px = 30;  // the growth's cap (Segmentation.maxGrowPx)
  void check() const;
  static AsyncMaskOptions from(const SegmentationOptions& segmentation);
};

struct FrameMask {
  cv::Mat1b mask;  // frame size, 255: dynamic
  int age = 0;        // processed frames (mask_for calls) since the segmented frame
  int input_age = 0;  // input frames since it (differs when frames were dropped)
  std::shared_ptr<const SegmentationResult> source;  // the segmentation it comes from
  ScheduleReason scheduled = ScheduleReason::None;  // this frame went to the stage, why
  bool waited = false;   // this frame waited for a fresh mask
  double wait_ms = 0;
  double propagation_cpu_ms = 0;  // this thread's CPU time carrying the mask (propagator or growing)
  // Age > 0 with the propagator: each carried instance, undilated, with its
  // median depth in this frame. Empty otherwise.
  std::vector<PropagatedInstance> instances;
};

class AsyncMasks {
 public:
  // `stage` is not owned and outlives this. dilation_px: what the fresh
  // masks are dilated by (Segmentation.maskDilation), applied to propagated
  // instances too.
  AsyncMasks(SegmentationStage& stage, AsyncMaskOptions options, std::optional<MaskPropagator> propagator = {},
             int dilation_px = 0);

  // bgr: the frame's colour image; frame_index: SensorFrame::index
  // (increasing); gray (8UC1) and depth (CV_32F metres, may be empty): for
  // the propagator, which then runs on every frame with a carried mask;
  // right (8UC1, may be empty): stereo's rectified right image, kept with a
  // segmented frame for the propagator's instance depths.
  FrameMask mask_for(const cv::Mat& bgr, std::size_t frame_index, const cv::Mat& gray = {},
                     const cv::Mat& depth = {}, const cv::Mat& right = {});

  // After tracking a frame: its pose (nullopt: not tracked), and for stereo
  // its keypoint depths as a sparse depth image (empty otherwise), for
  // propagating from it when it was segmented.
  void on_tracked(std::size_t frame_index, const std::optional<Eigen::Isometry3d>& T_cam_world,
                  cv::Mat1f sparse_depth = {});
  // on_tracked() would keep a sparse depth for this frame: it went to the
  // stage without a depth image and the propagator may start from it.
  bool wants_sparse_depth(std::size_t frame_index) const;

  // The next frame gets a segmentation slot if the stage is idle (a keyframe
  // candidate deferred for an old mask, weak tracking).
  void request_urgent() { scheduler_.request_urgent(); }

  // After tracking the frame of the last mask_for() call: a keyframe made
  // from it waits for its own mask (tracking/keyframe_hold.h), so it goes to
  // the stage now unless it already did. Until that mask is fresh, no other
  // request is made while the stage is busy (a threaded stage would drop the
  // queued one). Returns whether it was submitted now.
  bool segment_last(const cv::Mat& bgr, std::size_t frame_index);

  // The newest result usable at the last mask_for() call (null before the first).
  const std::shared_ptr<const SegmentationResult>& fresh() const { return fresh_; }

  std::size_t skipped() const { return stage_.skipped(); }
  std::size_t submitted() const { return stage_.submitted(); }

 private:
  bool stage_busy() const;
  void submit(const cv::Mat& bgr, std::size_t frame_index);
  // Moves the results usable at the processed frame `ordinal` into fresh_.
  void collect(std::size_t ordinal);
  // The processed-frame ordinal of a submitted frame.
  std::size_t ordinal_of(std::size_t frame_index) const;
  // Waits (threaded) or takes at once (deterministic) the result of `frame_index`.
  void wait_for(std::size_t frame_index);
  cv::Mat1b carried(const SegmentationResult& result, int age) const;
  cv::Mat1b propagated(std::size_t frame_index, const cv::Mat1b& gray, const cv::Mat1f& depth, int age,
                       std::vector<PropagatedInstance>& instances);
  std::optional<Eigen::Isometry3d> predicted_pose(std::size_t frame_index) const;

  SegmentationStage& stage_;
  AsyncMaskOptions options_;
  SegmentationScheduler scheduler_;
  std::shared_ptr<const SegmentationResult> fresh_;
  std::optional<std::size_t> needed_;  // segment_last(): the frame whose own mask is awaited
  // Deterministic: results segmented but not usable yet (modelled latency).
  std::deque<std::shared_ptr<const SegmentationResult>> pending_;
  // Ages count processed frames: each mask_for() call is one; the ordinal of
  // each submitted frame is kept until its result is superseded.
  std::size_t processed_ = 0;
  std::map<std::size_t, std::size_t> ordinals_;  // frame index -> ordinal

  // Propagation: what it needs of each submitted frame until its result is
  // used or superseded.
  struct Submitted {
    cv::Mat1b gray;
    cv::Mat1f depth;
    std::optional<Eigen::Isometry3d> T_cam_world;
    cv::Mat1b right;
  };
  std::optional<MaskPropagator> propagator_;
  int dilation_px_ = 0;
  std::map<std::size_t, Submitted> submitted_;
  cv::Mat1b pending_gray_;  // of the frame in mask_for()
  cv::Mat1f pending_depth_;
  cv::Mat1b pending_right_;
  std::optional<std::size_t> reset_from_;      // the fresh frame the propagator started from
  std::optional<std::size_t> last_propagated_;  // the frame it last carried the masks to (or reset_from_)
  // The last two tracked poses (frame index, T_cam_world), for the motion prediction.
  std::deque<std::pair<std::size_t, Eigen::Isometry3d>> poses_;
};

}  // namespace stillslam
