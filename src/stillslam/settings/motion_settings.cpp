#include "stillslam/settings/section_binders.h"
#include "stillslam/settings/section_keys.h"

namespace stillslam {

void bind_motion(const YamlReader& yaml, MotionOptions& options) {
  SectionKeys keys(yaml, "Motion", true);
  keys.flag("enabled", options.enabled, "MotionOptions.enabled");
  keys.integer("instanceFeatures", options.instance_features, "MotionOptions.instance_features", {1, 10000});
  keys.flag("watchObjects", options.watch_objects, "MotionOptions.watch_objects");
  keys.integer("span", options.span, "MotionOptions.span", {1, 100});
  keys.number("matchWindowPx", options.match_window_px, "MotionOptions.match_window_px", {0, 10000});
  keys.integer("personFrames", options.person_frames, "MotionOptions.person_frames", {1, 10000});
  keys.integer("defaultFrames", options.default_frames, "MotionOptions.default_frames", {1, 10000});
  keys.number("minIou", options.min_iou, "MotionOptions.min_iou", {0, 1, true});
  keys.number("objectMovingFactor", options.object_moving_factor, "MotionOptions.object_moving_factor", {2, 100});
  keys.number("objectMovingFloorPx", options.object_moving_floor_px, "MotionOptions.object_moving_floor_px", {1.5, 100});
  keys.integer("keptPointFrames", options.kept_point_frames, "MotionOptions.kept_point_frames", {0, 100000});
  keys.flag("keptPointsOutOfPose", options.kept_points_out_of_pose, "MotionOptions.kept_points_out_of_pose");
  keys.number("keptPointSigma", options.kept_point_sigma, "MotionOptions.kept_point_sigma", {1, 100});
  keys.integer("keptFeatures", options.kept_features, "MotionOptions.kept_features", {0, 10000});
  keys.number("keptFeaturesAreaFactor", options.kept_features_area_factor,
              "MotionOptions.kept_features_area_factor", {0, 10});
  keys.flag("keptPointsOutOfBA", options.kept_points_out_of_ba, "MotionOptions.kept_points_out_of_ba");
  keys.number("freeSpaceShare", options.free_space_share, "MotionOptions.free_space_share", {0, 1});
  keys.integer("freeSpaceFrames", options.free_space_frames, "MotionOptions.free_space_frames", {0, 100});
  keys.flag("freeSpaceVacated", options.free_space_vacated, "MotionOptions.free_space_vacated");
  keys.flag("freeSpaceNearer", options.free_space.count_nearer, "FreeSpaceOptions.count_nearer");
  keys.flag("predictedCheck", options.predicted_check, "MotionOptions.predicted_check");
  keys.number("placeRadius", options.place_radius_m, "MotionOptions.place_radius_m", {0, 10});
  keys.integer("placeMemoryFrames", options.place_memory_frames, "MotionOptions.place_memory_frames", {0, 100000});
  keys.flag("sparseView", options.sparse_view.enabled, "SparseViewOptions.enabled");
  keys.flag("sparseViewKeyframes", options.sparse_view.keyframes, "SparseViewOptions.keyframes");
  keys.flag("sparseViewPrior", options.sparse_view.prior, "SparseViewOptions.prior");
  keys.number("sparseViewFilterGain", options.sparse_view.filter_gain, "SparseViewOptions.filter_gain", {0, 1});
  keys.integer("sparseViewFilterFrames", options.sparse_view.filter_frames, "SparseViewOptions.filter_frames", {1, 100});
  keys.integer("sparseViewFilterAxes", options.sparse_view.filter_axes, "SparseViewOptions.filter_axes", {1, 3});
  keys.number("sparseViewKeyframePriorSigma", options.sparse_view.keyframe_prior_sigma,
              "SparseViewOptions.keyframe_prior_sigma", {0, 1});
  keys.integer("sparseViewSmoothFrames", options.sparse_view.smooth_frames, "SparseViewOptions.smooth_frames", {0, 100});
  keys.number("sparseViewMaskedShare", options.sparse_view.masked_share, "SparseViewOptions.masked_share", {0, 1});
  keys.integer("sparseViewInliers", options.sparse_view.inliers, "SparseViewOptions.inliers", {0, 100000});
  keys.number("sparseViewTrackedWeight", options.sparse_view.tracked_weight, "SparseViewOptions.tracked_weight",
              {0, 1});
  keys.reject_unknown_keys();
  keys.check([&] { options.check(); });
}

}  // namespace stillslam
