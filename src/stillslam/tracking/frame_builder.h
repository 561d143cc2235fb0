#pragma once
// Turns a SensorFrame into a tracking Frame. Order matters and is the point of
// the design: the colour image goes to the segmentation worker first; for
// stereo, ORB on the right image runs meanwhile on another thread; the left
// image WAITS for the dynamic mask and is extracted outside it (its whole
// feature budget goes to the static part of the view), and any keypoint left
// inside the mask is dropped before stereo/depth association, so no later
// stage ever sees a feature on a moving object. Without a worker the pipeline
// is identical minus the mask. With asynchronous segmentation
// (segmentation/async_masks.h) nothing waits on ordinary frames: the mask is
// this frame's own if it is ready, else the last one carried to this frame.
#include <cstddef>
#include <cstdint>
#include <memory>

#include "stillslam/features/orb_extractor.h"
#include "stillslam/features/stereo_matcher.h"
#include "stillslam/core/sensor_frame.h"
#include "stillslam/map/frame.h"
#include "stillslam/tracking/frame_dynamics.h"
#include "stillslam/tracking/motion_frame_stats.h"
#include "stillslam/segmentation/async_masks.h"
#include "stillslam/segmentation/segmentation_worker.h"

namespace stillslam {

class MotionStage;

struct FrameBuildStats {
  int keypoints_before = 0;  // extracted on the left/colour image (outside the dynamic mask)
  int keypoints_after = 0;   // after the dynamic filter
  int keypoints_with_depth = 0;
  int detections = 0;        // all detections of the segmenter
  double mask_coverage = 0;  // fraction of the image in the dynamic mask
  double held_coverage = 0;  // of which held over from instances the segmenter lost (MaskHold)
  double extraction_ms = 0;  // ORB on the left image (the right one ran meanwhile)
  double extraction_cpu_ms = 0;  // CPU time of this thread in the left-image extraction
  double segmentation_ms = 0;       // segmenter time on its own thread
  double segmentation_cpu_ms = 0;   // and its CPU time there (for this frame's own mask)
  double segmentation_wait_ms = 0;  // time this thread waited for the mask
  double propagation_cpu_ms = 0;    // async: CPU time of this thread carrying the last mask to this frame
  double association_ms = 0;        // stereo matching / depth lookup
  double total_ms = 0;
  // Processed frames since the segmented frame the mask comes from (0: fresh,
  // this frame's own; -1: no segmentation).
  int mask_age = -1;
  bool mask_waited = false;  // extraction waited for the mask (sync: always; async: too old)
  ScheduleReason segmentation_request = ScheduleReason::None;  // async: this frame went to the stage, why
  std::size_t segmentation_skips = 0;  // async: stale requests the stage skipped so far
  MotionFrameStats motion;  // Motion.enabled: the motion stage on this frame
};

class FrameBuilder {
 public:
  // `setup` must describe the undistorted (rectified for stereo) camera with
  // its bf. `segmentation` may be null (no masks); it is not owned.
  FrameBuilder(std::shared_ptr<const CameraSetup> setup, SensorType sensor, const OrbOptions& orb,
               SegmentationWorker* segmentation, StereoMatchOptions stereo_options = {});
  // Asynchronous segmentation (not owned; may be null: no masks).
  FrameBuilder(std::shared_ptr<const CameraSetup> setup, SensorType sensor, const OrbOptions& orb,
               AsyncMasks* async_segmentation, StereoMatchOptions stereo_options = {});
  // No segmentation.
  FrameBuilder(std::shared_ptr<const CameraSetup> setup, SensorType sensor, const OrbOptions& orb, std::nullptr_t,
               StereoMatchOptions stereo_options = {})
      : FrameBuilder(std::move(setup), sensor, orb, static_cast<SegmentationWorker*>(nullptr), stereo_options) {}

  // Throws stillslam::Error when the frame lacks the images the sensor needs.
  // `dynamics` (optional) receives the detections and the removed features.
  Frame build(const SensorFrame& input, std::uint64_t frame_id, FrameBuildStats* stats,
              FrameDynamics* dynamics = nullptr) const;

  bool segmentation_enabled() const { return segmentation_ != nullptr || async_ != nullptr; }
  // Motion-aware masks (not owned; null: class-only masks).
  void set_motion_stage(MotionStage* stage) { motion_ = stage; }

 private:
  std::shared_ptr<const CameraSetup> setup_;
  SensorType sensor_;
  OrbExtractor extractor_;
  SegmentationWorker* segmentation_;
  AsyncMasks* async_ = nullptr;
  StereoMatchOptions stereo_options_;
  MotionStage* motion_ = nullptr;
};

}  // namespace stillslam
