#pragma once
#include <string>
#include <vector>

namespace stillslam {

enum class SegmentationMode {
  Sync,   // every frame waits for its own mask (segmentation_worker.h)
  Async,  // own rate on the newest frame, masks carried between (segmentation_stage.h, async_masks.h)
};
const char* to_string(SegmentationMode mode);

// Segmentation.* settings.
struct SegmentationOptions {
  bool enabled = true;                        // Segmentation.enabled
  std::string model_path;                     // Segmentation.model (relative to the settings file)
  std::vector<std::string> classes{"person"}; // Segmentation.classes: COCO names or ids
  float score_threshold = 0.25f;              // Segmentation.scoreThreshold
  float nms_iou_threshold = 0.45f;            // Segmentation.nmsIouThreshold
  float mask_threshold = 0.5f;                // Segmentation.maskThreshold
  int mask_dilation = 0;                      // Segmentation.maskDilation, pixels
  // Segmentation.holdFrames: a dynamic instance the segmenter loses stays masked
  // this many frames (detections flicker; see mask_hold.h). 0: off.
  int hold_frames = 10;
  // Segmentation.threads: the size of OpenCV's process-wide thread pool (the DNN and ORB
  // extraction's parallel_for_), applied once by the application, not by a library call.
  // 1 (default) runs both serially on their calling threads; 0 keeps OpenCV's own setting.

  int threads = 1;
  // Segmentation.masksForClassesOnly: compute instance masks only for `classes` (SLAM only
  // needs the dynamic ones; saves ~1 ms per other detection). Other detections keep an empty mask.
  bool masks_for_classes_only = false;
  // Segmentation.agnosticNms: let a box suppress overlapping boxes of any class (the
  // default is class-aware NMS, so a "truck" box over a "bus" survives).
  bool agnostic_nms = false;
  // Segmentation.mode: sync or async.
  SegmentationMode mode = SegmentationMode::Sync;
  // Async: Segmentation.threadNice, the segmentation thread's nice value is
  // raised by this (Linux; 19 at most) so that tracking and local mapping get
  // a core before it (segmentation_stage.h). 0: the process's priority.
  // 10 on 2 cores: the tracking thread waited ~40 % less for a core in
  // --realtime runs (bench/README.md, issue #16).
  int thread_nice = 10;
  // Async: Segmentation.interval, a frame is segmented at least every this many processed frames.
  // 5: yolo11n-seg costs ~141 CPU-ms per call, 28 per frame at 5 (the 66 CPU-ms of 2 cores at 30 Hz).
  int interval = 5;
  // Async: Segmentation.maxMaskAge, a frame whose newest mask is older (in
  // processed frames: frames --realtime dropped do not count) waits for a fresh one.
  int max_mask_age = 15;
  // Async: Segmentation.keyframeMaskAge, tracking makes no keyframe from a
  // frame whose mask is older; it asks for the next segmentation slot.
  int keyframe_mask_age = 6;
  // Async: Segmentation.keyframeHold, instead the keyframe is made and held
  // from local mapping until its frame's own mask (requested for it) arrives
  // (tracking/keyframe_hold.h).
  bool keyframe_hold = true;
  // Async: Segmentation.heldEvidence, with keyframe_hold: the older points a
  // held keyframe matched count it in their static-evidence span at once, not
  // only when local mapping gets it (tracking/keyframe_hold.h).
  bool held_evidence = false;
  // Async: Segmentation.provisionalPoints, with keyframe_hold: such a keyframe
  // goes to local mapping at once and only its new depth points wait for the
  // frame's own mask, provisional (tracking/provisional_points.h).
  bool provisional_points = false;
  // Async: Segmentation.startCheck, the map's first keyframe made under a
  // carried mask is checked with its frame's own mask (requested for it) when
  // that comes: its points inside are culled, the start is not delayed
  // (tracking/keyframe_check.h).
  bool start_check = false;
  // Async: Segmentation.keyframeCheck, every other keyframe made under a
  // carried mask (age > 0) that is not held (keyframe_hold) goes to local
  // mapping at once, its frame to the segmenter, and its points inside its
  // own mask are culled or unlinked when that mask comes (keyframe_check.h).
  bool keyframe_check = false;
  // Async: Segmentation.checkNewPoints, with start_check or keyframe_check:
  // at the check, the points made since that keyframe (local mapping's
  // triangulations with it, later keyframes' points) that it sees inside its
  // own mask are culled too, not only unlinked from it.
  bool check_new_points = false;
  // Async with --deterministic: Segmentation.modelledLatency, the mask of
  // frame k is usable from frame k + this on (the segmenter's time in frames),
  // independent of timing. 5: one YOLO thread's ~140 ms at 30 Hz.
  int modelled_latency = 5;
  // Async: Segmentation.maxGrowPx, a carried mask grows at most this much in
  // all (without mask propagation, and the held-over instances): growing
  // without bound, old held masks covered most of the view.
  int max_grow_px = 30;
  // Async: Segmentation.urgentInliers, a frame tracked with fewer map-point
  // inliers asks for the next segmentation slot. 0: never.
  int urgent_inliers = 50;
  // Async: Segmentation.freshMaskCull, when the own mask of a segmented frame
  // arrives (it was built with a carried one), the map points that frame saw
  // on a person are culled (tracking/fresh_mask_check.h).
  bool fresh_mask_cull = false;
  // Async: Segmentation.nearPersonPxPerFrame, a keyframe made under a carried
  // mask makes no depth point from a keypoint within this many pixels per
  // frame of mask age (near_person_max_px at most) of a carried instance whose
  // median depth is within near_person_depth_band metres of the keypoint's
  // (tracking/near_person.h). 0: off.
  double near_person_px_per_frame = 0;
  int near_person_max_px = 40;          // Segmentation.nearPersonMaxPx
  double near_person_depth_band = 0.5;  // Segmentation.nearPersonDepthBand (metres)
  // Segmentation.nearPersonAtStart: the near-person rule on the map's first keyframe too.
  bool near_person_at_start = true;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

}  // namespace stillslam
