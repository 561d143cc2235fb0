#pragma once
#include "stillslam/optimize/pose_optimizer.h"
#include "stillslam/tracking/depth_point_check.h"
#include "stillslam/tracking/initial_view_check.h"
#include "stillslam/tracking/keyframe_budget.h"
#include "stillslam/tracking/motion_prior.h"
#include "stillslam/tracking/sparse_view.h"
#include "stillslam/tracking/static_evidence.h"
#include "stillslam/tracking/tracking_probe.h"

namespace stillslam {

struct TrackerOptions {
  int init_min_keypoints = 500;        // keypoints with depth needed to initialize
  // With segmentation on, the first keyframe is checked against each of the
  // next init_confirm_frames frames (tracking/initial_view_check.h): a person
  // the detector missed in one frame is usually found in one of the next,
  // and a view about to be hidden is not a good start. After
  // init_wait_frames rejected frames that had the depth, any frame with
  // enough depth starts the map.
  InitialViewCheckOptions initial_view;
  int init_confirm_frames = 2;
  // Without segmentation the same check, over this many next frames, keeps
  // the points that move (or that no frame confirms) out of the first
  // keyframe when it finds enough of them moving (init_unmasked_moving_share):
  // a view full of walking people would otherwise anchor the map on them.
  // 0 (the default): the map starts from the first frame with depth. 3
  // meets issue #20's bars (bench/README.md) but the frames it waits get no
  // pose, which the end-to-end tests that expect a pose on every frame refuse.
  int init_unmasked_confirm_frames = 0;
  // After such a start, for this many frames the first keyframe's points
  // count as static evidence, and no visual-odometry or keyframe depth point
  // is made where a match was rejected or that the previous frame did not
  // see in place (tracking/start_evidence.h). 0: the start check alone.
  int init_unmasked_trust_frames = 10;
  // The check leaves points out of the first keyframe only when it finds
  // something moving: of the first-frame points the confirming frames
  // matched, at least this share, and at least init_unmasked_moving_points of
  // them, found moving by one of the frames. Otherwise the whole first
  // keyframe is kept as a start without the check keeps it (no trust window
  // either); only the wait differs. 0 and 0: always filtered. Views without
  // movers show 1-5 % (mismatches, depth noise), views with walkers 5-45 %.
  double init_unmasked_moving_share = 0.1;
  int init_unmasked_moving_points = 0;
  int init_wait_frames = 30;
  int max_frames_between_keyframes = 30;  // ORB-SLAM: fps
  int min_frames_between_keyframes = 0;
  KeyFrameBudgetOptions keyframe_budget;  // keyframes per second of input (tracking/keyframe_budget.h)
  // A frame with fewer inliers takes its keyframe outside the budget: the
  // budget holds while tracking is comfortable, not at a map's start or when
  // the view is mostly new or hidden (bench/README.md, issue #21 session 10).
  int keyframe_budget_inliers = 150;
  // A weak frame interrupts the mapper's local BA only with fewer inliers (tracking/keyframe_admission.h).
  int interrupt_inliers = 100;
  float motion_search_radius = 7.f;    // pixels at level 0 (doubled on a retry)
  float local_map_search_th = 3.f;
  float reference_search_th = 5.f;     // wide window when the motion model fails
  float lost_search_th = 10.f;         // very wide window while lost
  int min_local_map_inliers = 30;
  std::size_t max_local_keyframes = 80;
  int close_points_tracked_min = 100;  // keyframe when fewer close points are tracked...
  int close_points_untracked_min = 70; // ...and this many close points are not
  int new_keyframe_points = 100;       // points created from depth per keyframe (beyond close ones)
  DepthPointCheckOptions new_point_check;  // only points the previous frame saw in place
  // A keypoint whose map-point match was an outlier of the final pose
  // optimization gets no new depth point at a keyframe (ORB-SLAM keeps such a
  // match in the keyframe for local BA to judge instead). Off by default, see
  // DepthPointCheckOptions::enabled.
  bool skip_outlier_keypoints = false;
  // A map point rejected as an outlier in this many consecutive frames that
  // matched it is culled (0: never, the default: on the issue #20 renders it
  // culled static points too, see bench/README.md); Tracker::cull_outlier_streaks.
  int outlier_streak_cull = 0;
  PoseOptimizerOptions pose;
  // Motion-model, reference-keyframe and local-map poses from the map points
  // with static evidence (tracking/static_evidence.h).
  StaticEvidenceOptions static_evidence;
  // The motion model's prediction as a prior in the motion-model and
  // local-map pose stages (tracking/motion_prior.h).
  MotionPriorOptions motion_prior;
  // Track against the map without changing it (a loaded map): no keyframes,
  // no map points; never initializes a map of its own.
  bool localization_only = false;
  // No keyframe from a frame whose dynamic mask is older than this many
  // processed frames (Frame::mask_age; set by System from
  // Segmentation.keyframeMaskAge in async mode); the keyframe is deferred to
  // a later frame. -1: any age.
  int max_keyframe_mask_age = -1;
  // New depth points of a keyframe whose frame's dynamic mask is older than
  // this many processed frames are provisional (MapPoint::is_provisional; set
  // by System from Segmentation.keyframeMaskAge with
  // Segmentation.provisionalPoints): the frame does not track with them and
  // tracking/provisional_points.h confirms or culls them when the frame's own
  // mask comes. -1: never.
  int provisional_mask_age = -1;
  // The crowd fallback when masks hide most of the view (tracking/sparse_view.h,
  // Motion.sparseView*).
  SparseViewOptions sparse_view;
  // Diagnostics only (tracking/tracking_probe.h): sees every stage's result.
  TrackingProbe probe;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

}  // namespace stillslam
