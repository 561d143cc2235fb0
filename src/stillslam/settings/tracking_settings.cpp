#include "stillslam/settings/section_binders.h"
#include "stillslam/settings/section_keys.h"

namespace stillslam {

void bind_tracking(const YamlReader& yaml, double fps, TrackerOptions& tracker, RelocalizerOptions& relocalizer) {
  // As ORB-SLAM: at most one second of frames between keyframes.
  tracker.max_frames_between_keyframes = static_cast<int>(fps);
  SectionKeys keys(yaml, "Tracking", true);
  // Map initialization (tracking/initial_view_check.h).
  keys.integer("initMinKeypoints", tracker.init_min_keypoints, "TrackerOptions.init_min_keypoints");
  keys.integer("initConfirmFrames", tracker.init_confirm_frames, "TrackerOptions.init_confirm_frames");
  keys.integer("initWaitFrames", tracker.init_wait_frames, "TrackerOptions.init_wait_frames");
  InitialViewCheckOptions& view = tracker.initial_view;
  keys.number("initMaxMaskedFraction", view.max_masked_fraction, "InitialViewCheckOptions.max_masked_fraction");
  keys.number("initMaxMovingShare", view.max_moving_share, "InitialViewCheckOptions.max_moving_share");
  keys.integer("initMinMatches", view.min_matches, "InitialViewCheckOptions.min_matches");
  keys.number("initMaxReprojectionError", view.max_reprojection_error_px,
              "InitialViewCheckOptions.max_reprojection_error_px");
  // Keyframe decision.
  keys.integer("maxFramesBetweenKeyframes", tracker.max_frames_between_keyframes,
               "TrackerOptions.max_frames_between_keyframes");
  keys.integer("minFramesBetweenKeyframes", tracker.min_frames_between_keyframes,
               "TrackerOptions.min_frames_between_keyframes");
  keys.integer("closePointsTrackedMin", tracker.close_points_tracked_min, "TrackerOptions.close_points_tracked_min");
  keys.integer("closePointsUntrackedMin", tracker.close_points_untracked_min,
               "TrackerOptions.close_points_untracked_min");
  keys.integer("newKeyframePoints", tracker.new_keyframe_points, "TrackerOptions.new_keyframe_points");
  keys.flag("newPointCheck", tracker.new_point_check.enabled);
  keys.flag("newPointSkipOutliers", tracker.skip_outlier_keypoints);
  keys.integer("outlierStreakCull", tracker.outlier_streak_cull, "TrackerOptions.outlier_streak_cull");
  keys.number("newPointCheckRadius", tracker.new_point_check.radius, "DepthPointCheckOptions.radius");
  // Search windows and the local map.
  keys.number("motionSearchRadius", tracker.motion_search_radius, "TrackerOptions.motion_search_radius");
  keys.number("localMapSearchRadius", tracker.local_map_search_th, "TrackerOptions.local_map_search_th");
  keys.number("referenceSearchRadius", tracker.reference_search_th, "TrackerOptions.reference_search_th");
  keys.number("lostSearchRadius", tracker.lost_search_th, "TrackerOptions.lost_search_th");
  keys.integer("minLocalMapInliers", tracker.min_local_map_inliers, "TrackerOptions.min_local_map_inliers");
  keys.count("maxLocalKeyframes", tracker.max_local_keyframes, "TrackerOptions.max_local_keyframes");
  // Motion-only pose optimization.
  keys.integer("poseRounds", tracker.pose.rounds, "PoseOptimizerOptions.rounds");
  keys.integer("poseIterations", tracker.pose.iterations_per_round, "PoseOptimizerOptions.iterations_per_round");
  keys.check([&] { tracker.check(); });
  // Relocalization.
  keys.integer("relocMinBowMatches", relocalizer.min_bow_matches, "RelocalizerOptions.min_bow_matches");
  keys.integer("relocMinRansacInliers", relocalizer.min_ransac_inliers, "RelocalizerOptions.min_ransac_inliers");
  keys.integer("relocMinInliers", relocalizer.min_inliers, "RelocalizerOptions.min_inliers");
  keys.reject_unknown_keys();
  keys.check([&] { relocalizer.check(); });
}

}  // namespace stillslam
