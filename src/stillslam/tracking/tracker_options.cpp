#include "stillslam/tracking/tracker_options.h"

#include <algorithm>

#include "stillslam/core/option_check.h"

namespace stillslam {

void TrackerOptions::check() const {
  using namespace option_check;
  at_least("TrackerOptions.init_min_keypoints", init_min_keypoints, 1);
  at_least("TrackerOptions.max_keyframe_mask_age", max_keyframe_mask_age, -1);
  at_least("TrackerOptions.provisional_mask_age", provisional_mask_age, -1);
  initial_view.check();
  sparse_view.check();
  at_least("TrackerOptions.init_confirm_frames", init_confirm_frames, 0);
  at_least("TrackerOptions.init_unmasked_confirm_frames", init_unmasked_confirm_frames, 0);
  in_range("TrackerOptions.init_unmasked_trust_frames", init_unmasked_trust_frames, 0, 1000);
  in_range("TrackerOptions.init_unmasked_moving_share", init_unmasked_moving_share, 0, 1);
  in_range("TrackerOptions.init_unmasked_moving_points", init_unmasked_moving_points, 0, 100000);
  at_least("TrackerOptions.init_wait_frames", init_wait_frames, 0);
  at_least("TrackerOptions.max_frames_between_keyframes", max_frames_between_keyframes, 0);
  in_range("TrackerOptions.min_frames_between_keyframes", min_frames_between_keyframes, 0,
           std::max(max_frames_between_keyframes, 0));
  keyframe_budget.check();
  in_range("TrackerOptions.keyframe_budget_inliers", keyframe_budget_inliers, 0, 50000);
  in_range("TrackerOptions.interrupt_inliers", interrupt_inliers, 0, 50000);
  above("TrackerOptions.motion_search_radius", motion_search_radius, 0);
  above("TrackerOptions.local_map_search_th", local_map_search_th, 0);
  above("TrackerOptions.reference_search_th", reference_search_th, 0);
  above("TrackerOptions.lost_search_th", lost_search_th, 0);
  at_least("TrackerOptions.min_local_map_inliers", min_local_map_inliers, 1);
  at_least("TrackerOptions.max_local_keyframes", static_cast<double>(max_local_keyframes), 1);
  at_least("TrackerOptions.close_points_tracked_min", close_points_tracked_min, 0);
  at_least("TrackerOptions.close_points_untracked_min", close_points_untracked_min, 0);
  at_least("TrackerOptions.new_keyframe_points", new_keyframe_points, 0);
  new_point_check.check();
  near_person.check();
  at_least("TrackerOptions.outlier_streak_cull", outlier_streak_cull, 0);
  pose.check();
  static_evidence.check();
  motion_prior.check();
}

}  // namespace stillslam
