#pragma once
// What happened to one input frame (for stats.json and summaries).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "stillslam/publish/snapshots.h"
#include "stillslam/tracking/frame_builder.h"
#include "stillslam/tracking/motion_prior.h"
#include "stillslam/tracking/tracking_state.h"

namespace stillslam {

struct FrameStats {
  std::size_t index = 0;
  double timestamp = 0;
  TrackingState state = TrackingState::NotInitialized;
  std::string reason;
  FrameBuildStats build;   // features before/after the filter, detections, mask, times
  int matches = 0;
  int inliers = 0;
  bool keyframe = false;
  bool keyframe_deferred = false;  // due, but the mask was older than Segmentation.keyframeMaskAge
  MotionPriorFrame motion_prior;  // TrackingResult::motion_prior
  // Made with a carried mask, held until its own mask comes (keyframe_hold.h), or with
  // Segmentation.provisionalPoints its new points provisional until then (provisional_points.h), or
  // with Segmentation.startCheck / keyframeCheck in use at once and checked then (keyframe_check.h).
  bool keyframe_held = false;
  // Points culled or unlinked as held keyframes were released (or provisional points or checked
  // keyframes checked) before this frame was tracked.
  int held_points_removed = 0;
  int fresh_mask_culled = 0;  // map points culled when an earlier frame's own mask arrived (fresh_mask_check.h)
  double tracking_ms = 0;  // tracker only (map matching, pose optimization, keyframe decision)
  double mapping_ms = 0;   // synchronous local mapping after this frame (deterministic mode)
  double total_ms = 0;     // frame builder + tracker (+ synchronous mapping)
  double tracking_cpu_ms = 0;  // CPU time of the calling thread in the tracker
  double total_cpu_ms = 0;     // CPU time of the calling thread for the whole frame
                               // (without the segmentation worker / right-image thread)
  // Of total_ms, the time the calling thread was ready but waited for a core
  // (core/thread_run_queue_wait.h; 0 where not available).
  double core_wait_ms = 0;
  double publish_ms = 0;       // snapshots for the publish layer, after total_ms
  // Frame arrival to pose (dataset runner): from when the frame was due
  // (--realtime: its timestamp; else when the runner took it) to the end of
  // process().
  double latency_ms = 0;
  bool has_pose = false;
  // This frame started the map from an earlier frame (Tracking.initConfirmFrames,
  // initUnmaskedConfirmFrames): the frames the start waited on, which had no pose
  // when they were processed, posed now (the first keyframe's frame at the map's
  // origin, each confirming frame at the start check's motion from it), oldest
  // first. Their records are in the trajectory; DatasetRunner marks their stats.
  // The frame snapshot carries the same list (publish layer).
  using EarlierPose = FrameSnapshot::EarlierPose;
  std::vector<EarlierPose> start_frames_posed;
  // Set on a frame the start waited on once the map started (DatasetRunner):
  // has_pose is then true while state and reason stay as they were when it was processed.
  bool posed_at_start = false;
  std::uint64_t map_id = 0;  // the active map after tracking (atlas)
  bool new_map = false;      // a new map starts with the next frame
  bool merged = false;       // the active map was merged into an older one
  int loops_closed = 0;      // by loop closing so far (all maps)
  bool global_bundle_adjustment_running = false;  // after this frame
};

// Marks the frames `latest` posed at the map's start among `frames` (the
// stats of the frames processed before it): has_pose and posed_at_start.
inline void mark_start_frames_posed(std::vector<FrameStats>& frames, const FrameStats& latest) {
  for (const FrameStats::EarlierPose& p : latest.start_frames_posed) {
    for (auto f = frames.rbegin(); f != frames.rend(); ++f) {
      if (f->index != p.index) continue;
      f->has_pose = true;
      f->posed_at_start = true;
      break;
    }
  }
}

}  // namespace stillslam
