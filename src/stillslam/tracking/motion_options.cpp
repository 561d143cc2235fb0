#include "stillslam/tracking/motion_options.h"

#include "stillslam/core/option_check.h"

namespace stillslam {

void MotionOptions::check() const {
  using namespace option_check;
  in_range("MotionOptions.instance_features", instance_features, 1, 10000);
  in_range("MotionOptions.span", span, 1, 100);
  in_range("MotionOptions.person_frames", person_frames, 1, 10000);
  in_range("MotionOptions.default_frames", default_frames, 1, 10000);
  in_half_open("MotionOptions.min_iou", min_iou, 0, 1);
  in_range("MotionOptions.kept_point_frames", kept_point_frames, 0, 100000);
  in_range("MotionOptions.kept_point_sigma", kept_point_sigma, 1, 100);
  in_range("MotionOptions.kept_features", kept_features, 0, 10000);
  in_range("MotionOptions.kept_features_area_factor", kept_features_area_factor, 0, 10);
  in_range("MotionOptions.place_radius_m", place_radius_m, 0, 10);
  in_range("MotionOptions.place_memory_frames", place_memory_frames, 0, 100000);
  in_range("MotionOptions.object_moving_factor", object_moving_factor, 2, 100);
  in_range("MotionOptions.object_moving_floor_px", object_moving_floor_px, 1.5, 100);
  in_range("MotionOptions.free_space_share", free_space_share, 0, 1);
  in_range("MotionOptions.match_window_px", match_window_px, 0, 10000);
  in_range("MotionOptions.free_space_frames", free_space_frames, 0, 100);
  free_space.check();
  check_options().check();
  sparse_view.check();
}

InstanceMotionCheckOptions MotionOptions::check_options() const {
  InstanceMotionCheckOptions o;
  o.span = span;
  o.window_px = match_window_px;
  o.evidence.default_frames = default_frames;
  o.evidence.frames_by_class["person"] = person_frames;
  o.evidence.object_moving_factor = object_moving_factor;
  o.evidence.object_moving_floor_px = object_moving_floor_px;
  return o;
}

}  // namespace stillslam
