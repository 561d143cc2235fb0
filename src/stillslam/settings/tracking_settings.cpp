#include "stillslam/settings/section_binders.h"
#include "stillslam/settings/section_keys.h"

namespace stillslam {

void bind_tracking(const YamlReader& yaml, double fps, TrackerOptions& tracker, RelocalizerOptions& relocalizer) {
  // As ORB-SLAM: at most one second of frames between keyframes.
  tracker.max_frames_between_keyframes = static_cast<int>(fps);
  SectionKeys keys(yaml, "Tracking", true);
  // Map initialization (tracking/initial_view_check.h).
  keys.integer("initMinKeypoints", tracker.init_min_keypoints, "TrackerOptions.init_min_keypoints", {1, 50000});
  keys.integer("initConfirmFrames", tracker.init_confirm_frames, "TrackerOptions.init_confirm_frames", {0, 100});
  keys.integer("initUnmaskedConfirmFrames", tracker.init_unmasked_confirm_frames,
               "TrackerOptions.init_unmasked_confirm_frames", {0, 100});
  keys.integer("initUnmaskedTrustFrames", tracker.init_unmasked_trust_frames,
               "TrackerOptions.init_unmasked_trust_frames", {0, 1000});
  keys.number("initUnmaskedMovingShare", tracker.init_unmasked_moving_share,
              "TrackerOptions.init_unmasked_moving_share", {0, 1});
  keys.integer("initUnmaskedMovingPoints", tracker.init_unmasked_moving_points,
               "TrackerOptions.init_unmasked_moving_points", {0, 100000});
  keys.integer("initWaitFrames", tracker.init_wait_frames, "TrackerOptions.init_wait_frames", {0, 100000});
  InitialViewCheckOptions& view = tracker.initial_view;
  keys.number("initMaxMaskedFraction", view.max_masked_fraction, "InitialViewCheckOptions.max_masked_fraction", {0, 1});
  keys.number("initMaxMovingShare", view.max_moving_share, "InitialViewCheckOptions.max_moving_share", {0, 1});
  keys.number("initMaxMovingShareUnmasked", view.max_moving_share_unmasked,
              "InitialViewCheckOptions.max_moving_share_unmasked", {0, 1});
  keys.integer("initMinMatches", view.min_matches, "InitialViewCheckOptions.min_matches", {1, 50000});
  keys.number("initMaxReprojectionError", view.max_reprojection_error_px,
              "InitialViewCheckOptions.max_reprojection_error_px", {0, 100, true});
  keys.number("initMaxReprojectionErrorUnmasked", view.max_reprojection_error_unmasked_px,
              "InitialViewCheckOptions.max_reprojection_error_unmasked_px", {0, 100, true});
  keys.number("initMovingFactorUnmasked", view.moving_factor_unmasked, "InitialViewCheckOptions.moving_factor_unmasked",
              {1, 100});
  // Keyframe decision.
  keys.integer("maxFramesBetweenKeyframes", tracker.max_frames_between_keyframes,
               "TrackerOptions.max_frames_between_keyframes", {0, 100000});
  keys.integer("minFramesBetweenKeyframes", tracker.min_frames_between_keyframes,
               "TrackerOptions.min_frames_between_keyframes", {0, 100000});
  keys.number("keyframesPerSecond", tracker.keyframe_budget.per_second, "KeyFrameBudgetOptions.per_second", {0, 1000});
  keys.integer("interruptInliers", tracker.interrupt_inliers, "TrackerOptions.interrupt_inliers", {0, 50000});
  keys.number("keyframeBurst", tracker.keyframe_budget.burst, "KeyFrameBudgetOptions.burst", {1, 1000});
  keys.integer("keyframeBudgetStartKeyframes", tracker.keyframe_budget.start_keyframes,
               "KeyFrameBudgetOptions.start_keyframes", {0, 1000});
  keys.number("keyframeBudgetStartSeconds", tracker.keyframe_budget.start_seconds,
              "KeyFrameBudgetOptions.start_seconds", {0, 1000});
  keys.integer("keyframeBudgetInliers", tracker.keyframe_budget_inliers, "TrackerOptions.keyframe_budget_inliers",
               {0, 50000});
  keys.integer("closePointsTrackedMin", tracker.close_points_tracked_min,
               "TrackerOptions.close_points_tracked_min", {0, 50000});
  keys.integer("closePointsUntrackedMin", tracker.close_points_untracked_min,
               "TrackerOptions.close_points_untracked_min", {0, 50000});
  keys.integer("newKeyframePoints", tracker.new_keyframe_points, "TrackerOptions.new_keyframe_points", {0, 50000});
  keys.flag("newPointCheck", tracker.new_point_check.enabled);
  keys.flag("newPointSkipOutliers", tracker.skip_outlier_keypoints);
  keys.integer("outlierStreakCull", tracker.outlier_streak_cull, "TrackerOptions.outlier_streak_cull", {0, 1000});
  keys.number("newPointCheckRadius", tracker.new_point_check.radius, "DepthPointCheckOptions.radius", {0, 100, true});
  // Search windows and the local map.
  keys.number("motionSearchRadius", tracker.motion_search_radius,
              "TrackerOptions.motion_search_radius", {0, 1000, true});
  keys.number("localMapSearchRadius", tracker.local_map_search_th,
              "TrackerOptions.local_map_search_th", {0, 1000, true});
  keys.number("referenceSearchRadius", tracker.reference_search_th,
              "TrackerOptions.reference_search_th", {0, 1000, true});
  keys.number("lostSearchRadius", tracker.lost_search_th, "TrackerOptions.lost_search_th", {0, 1000, true});
  keys.integer("minLocalMapInliers", tracker.min_local_map_inliers, "TrackerOptions.min_local_map_inliers", {1, 50000});
  keys.count("maxLocalKeyframes", tracker.max_local_keyframes, "TrackerOptions.max_local_keyframes", {1, 10000});
  // Motion-only pose optimization.
  keys.integer("poseRounds", tracker.pose.rounds, "PoseOptimizerOptions.rounds", {1, 100});
  keys.integer("poseIterations", tracker.pose.iterations_per_round,
               "PoseOptimizerOptions.iterations_per_round", {1, 1000});
  keys.flag("staticEvidencePose", tracker.static_evidence.enabled);
  keys.integer("staticEvidenceSpan", tracker.static_evidence.min_span_frames,
               "StaticEvidenceOptions.min_span_frames", {0, 100000});
  keys.integer("staticEvidenceMinPoints", tracker.static_evidence.min_points,
               "StaticEvidenceOptions.min_points", {3, 50000});
  keys.integer("staticEvidenceQuietFrames", tracker.static_evidence.quiet_frames,
               "StaticEvidenceOptions.quiet_frames", {0, 100000});
  keys.number("motionPriorSigma", tracker.motion_prior.sigma_translation, "MotionPriorOptions.sigma_translation",
              {0, 10});
  keys.number("motionPriorRotationSigma", tracker.motion_prior.sigma_rotation, "MotionPriorOptions.sigma_rotation",
              {0, 10, true});
  keys.number("motionPriorDeadZone", tracker.motion_prior.dead_zone, "MotionPriorOptions.dead_zone", {0, 10});
  keys.number("motionPriorGate", tracker.motion_prior.gate, "MotionPriorOptions.gate", {0, 10});
  keys.flag("motionPriorRefit", tracker.motion_prior.refit);
  keys.check([&] { tracker.check(); });
  // Relocalization.
  keys.integer("relocMinBowMatches", relocalizer.min_bow_matches, "RelocalizerOptions.min_bow_matches", {1, 50000});
  keys.integer("relocMinRansacInliers", relocalizer.min_ransac_inliers,
               "RelocalizerOptions.min_ransac_inliers", {1, 50000});
  keys.integer("relocMinInliers", relocalizer.min_inliers, "RelocalizerOptions.min_inliers", {1, 50000});
  keys.reject_unknown_keys();
  keys.check([&] { relocalizer.check(); });
}

}  // namespace stillslam
