#include "stillslam/segmentation/segmentation_options.h"

#include "stillslam/core/option_check.h"

namespace stillslam {

const char* to_string(SegmentationMode mode) { return mode == SegmentationMode::Async ? "async" : "sync"; }

void SegmentationOptions::check() const {
  using namespace option_check;
  if (classes.empty()) throw OptionError("SegmentationOptions.classes", "empty", "must name at least one class");
  in_range("SegmentationOptions.score_threshold", score_threshold, 0, 1);
  in_half_open("SegmentationOptions.nms_iou_threshold", nms_iou_threshold, 0, 1);
  in_open("SegmentationOptions.mask_threshold", mask_threshold, 0, 1);
  at_least("SegmentationOptions.mask_dilation", mask_dilation, 0);
  at_least("SegmentationOptions.hold_frames", hold_frames, 0);
  at_least("SegmentationOptions.threads", threads, 0);
  at_least("SegmentationOptions.interval", interval, 1);
  at_least("SegmentationOptions.max_mask_age", max_mask_age, 0);
  at_least("SegmentationOptions.keyframe_mask_age", keyframe_mask_age, 0);
  at_least("SegmentationOptions.modelled_latency", modelled_latency, 0);
  at_least("SegmentationOptions.urgent_inliers", urgent_inliers, 0);
  at_least("SegmentationOptions.max_grow_px", max_grow_px, 0);
  in_range("SegmentationOptions.thread_nice", thread_nice, 0, 19);
  in_range("SegmentationOptions.near_person_px_per_frame", near_person_px_per_frame, 0, 100);
  in_range("SegmentationOptions.near_person_max_px", near_person_max_px, 0, 1000);
  in_half_open("SegmentationOptions.near_person_depth_band", near_person_depth_band, 0, 100);
  if (held_evidence && (!keyframe_hold || provisional_points)) {
    throw OptionError("SegmentationOptions.held_evidence", "1",
                      "needs keyframe_hold (Segmentation.keyframeHold: 1) without provisional_points "
                      "(Segmentation.provisionalPoints: 0): it acts on keyframes held from local mapping");
  }
  if (provisional_points && !keyframe_hold) {
    throw OptionError("SegmentationOptions.provisional_points", "1",
                      "needs keyframe_hold (Segmentation.keyframeHold: 1): it decides which keyframes wait "
                      "for their own mask");
  }
  if ((start_check || keyframe_check) && provisional_points) {
    throw OptionError(start_check ? "SegmentationOptions.start_check" : "SegmentationOptions.keyframe_check", "1",
                      "cannot be combined with provisional_points (Segmentation.provisionalPoints: 1): a "
                      "keyframe is either checked with its points in use or its points wait");
  }
  if (check_new_points && !start_check && !keyframe_check) {
    throw OptionError("SegmentationOptions.check_new_points", "1",
                      "needs start_check or keyframe_check (Segmentation.startCheck / Segmentation.keyframeCheck: 1)");
  }
  if (modelled_latency > max_mask_age) {
    throw OptionError("SegmentationOptions.modelled_latency", option_check::text(modelled_latency),
                      "must be at most max_mask_age (" + option_check::text(max_mask_age) + ")");
  }
}

}  // namespace stillslam
