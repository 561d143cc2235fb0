#pragma once
#include "stillslam/optimize/pose_optimizer.h"

namespace stillslam {

struct TrackerOptions {
  int init_min_keypoints = 500;        // keypoints with depth needed to initialize
  // The extractor puts its whole budget outside the dynamic mask, so 500
  // keypoints can all sit on a sliver of scene when people fill the view; a
  // map started there is poorly conditioned. Frames with more of the image
  // masked than this do not initialize, for at most init_masked_wait_frames
  // such frames (then any frame with enough depth does).
  double init_max_masked_fraction = 0.5;
  int init_masked_wait_frames = 30;
  int max_frames_between_keyframes = 30;  // ORB-SLAM: fps
  int min_frames_between_keyframes = 0;
  float motion_search_radius = 7.f;    // pixels at level 0 (doubled on a retry)
  float local_map_search_th = 3.f;
  float reference_search_th = 5.f;     // wide window when the motion model fails
  float lost_search_th = 10.f;         // very wide window while lost
  int min_local_map_inliers = 30;
  std::size_t max_local_keyframes = 80;
  int close_points_tracked_min = 100;  // keyframe when fewer close points are tracked...
  int close_points_untracked_min = 70; // ...and this many close points are not
  int new_keyframe_points = 100;       // points created from depth per keyframe (beyond close ones)
  PoseOptimizerOptions pose;
  // Track against the map without changing it (a loaded map): no keyframes,
  // no map points; never initializes a map of its own.
  bool localization_only = false;
};

}  // namespace stillslam
