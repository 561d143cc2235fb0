#pragma once
// What the motion stage (motion_stage.h) did to one frame, for stats.json.
namespace stillslam {

struct MotionFrameStats {
  bool judged = false;        // the frame had a fresh segmentation and went through the check
  int static_instances = 0;   // instances of a dynamic class kept as static (left out of the mask)
  int moving_instances = 0;   // instances of other classes masked because they move
  // Of those, found moving in this frame at its predicted pose (Motion.predictedCheck).
  int predicted_moving_instances = 0;
  // Features the mask removed (the extractor's thinned count), by why the
  // pixel was masked: its class, or the check's verdict that it moves.
  int features_removed_by_class = 0;
  int features_removed_by_motion = 0;
  // Features used for tracking on instances of a dynamic class kept as static.
  int features_kept_by_motion = 0;
  int instance_features = 0;  // extracted inside the mask for the check only
  int map_points_culled = 0;  // on instances found moving, after tracking
  // The crowd fallback's action on the frame (tracking/sparse_view.h,
  // SparseView: 0 none, 1 tracked, 2 blended, 3 predicted, 4 no map start).
  int sparse_view = 0;
};

}  // namespace stillslam
