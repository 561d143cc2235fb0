#pragma once
// Settings of the motion-aware dynamic handling (issue #19, `Motion.*`):
// segmented instances are judged by their motion (instance_motion_check.h)
// instead of by class alone. Off by default (see config/README.md).
#include "stillslam/tracking/free_space_check.h"
#include "stillslam/tracking/instance_motion_check.h"
#include "stillslam/tracking/instance_places.h"
#include "stillslam/tracking/sparse_view.h"

namespace stillslam {

struct MotionOptions {
  bool enabled = false;
  // ORB features extracted inside the masked area (kept apart from tracking)
  // so masked instances can be judged too.
  int instance_features = 200;
  // Objects not (yet) masked get features of their own from that budget too,
  // so a small one has enough matches to be judged (the frame's features
  // are spread over the whole view).
  bool watch_objects = true;
  int span = 6;            // frames between the two views compared
  // The check matches a feature only with the earlier view's features
  // predicted within this many pixels of it (0: all pairs).
  double match_window_px = 0;
  int person_frames = 10;  // agreeing frames a person needs before it is kept as static
  int default_frames = 10; // the same for every other class
  double min_iou = 0.3;    // mask overlap for an instance to keep its id across segmentations
  // An object (not of a dynamic class) disagrees above max(factor x the
  // background's median residual, floor): lower than a person's 3x / 3 px.
  double object_moving_factor = 2.0;
  double object_moving_floor_px = 2.0;
  // Map points matched on a person kept as static are culled this many frames
  // after they were first matched there (0: never): a seated person still
  // sways and breathes, and a point kept longer carries that into the pose
  // (30: bench/README.md, issue #19 session 10).
  int kept_point_frames = 30;
  // Matches on a person kept as static take no part in the frame's pose
  // (tracking's pose stages and the final trajectory refinement) when enough
  // other matches remain; they are still classified, tracked and counted
  // (tracking/static_evidence.h, system/trajectory_refinement.h).
  // Off: no gain measured yet (bench/README.md, issue #19 session 11).
  bool kept_points_out_of_pose = false;
  // Map points flagged on a person kept as static take no part in local BA
  // (mapping/local_bundle_adjustment.h): a swaying person moves neither the
  // keyframes nor its own points there; tracking still matches them.
  bool kept_points_out_of_ba = false;
  // Matches on a person kept as static count in the frame's pose (tracking's
  // pose stages and the final trajectory refinement) with this many times
  // their keypoint's sigma: a larger value lets its sway pull the pose less
  // without leaving its points out (1: as any other match).
  double kept_point_sigma = 1;
  // A person kept as static gets features of its own, up to this many
  // (extracted on its pixels like the masked instances' features), while the
  // frame's ORBextractor.nFeatures go to the rest of the view as if the
  // person were masked: keeping a person then takes no features from the
  // background. 0: the frame's features cover the kept person too.
  int kept_features = 0;
  // With kept_features: the kept people's budget is instead this factor x
  // ORBextractor.nFeatures x their share of the image's pixels (at most
  // kept_features), about what the frame's extraction gives them when they
  // are not left out; 0: kept_features as it is.
  double kept_features_area_factor = 0;
  // An object (not of a dynamic class) without a verdict from its matched
  // features is also found moving from depth (tracking/free_space_check.h):
  // when at least this share of its sampled pixels, and 3x the share of the
  // pixels of no instance, were seen through in the view `span` frames
  // earlier (0: never; needs a depth image and no lens distortion). 0.3 was
  // the bar tried.
  // Off until measured on more renders (bench/README.md, issue #19 session 11).
  double free_space_share = 0;
  // The view that depth check compares with: this many judged frames
  // earlier (0: `span`). A slowly pushed chair moves a few centimetres over
  // 6 frames, less than the check's gap.
  int free_space_frames = 0;
  // That check also the other way round (Motion.freeSpaceVacated): the
  // object's pixels in the earlier view put into this one; the share lying
  // where this view sees farther is the share of its old place it has left.
  // An object at the image border moving out of the view shows only its
  // trailing side, whose new place overlaps the old one.
  bool free_space_vacated = false;
  // free_space.count_nearer (Motion.freeSpaceNearer): pixels the earlier view
  // saw nearer count too, except on the people masked then.
  FreeSpaceOptions free_space;
  int free_space_span() const { return free_space_frames > 0 ? free_space_frames : span; }
  // A new instance within this distance (world frame) of where one of its
  // class was last seen takes over its evidence (instance_places.h); 0: never.
  double place_radius_m = 0.5;
  int place_memory_frames = 300;  // judged frames a place is remembered
  // Unmasked objects are also judged before the frame is tracked, at the
  // pose tracking predicts for it (MotionStage::judge_predicted), so an
  // object found moving loses its features in that frame already rather than
  // from the next one.
  bool predicted_check = false;
  // The crowd fallback (Motion.sparseView*): the tracker's, with or without
  // `enabled` above (System copies it into TrackerOptions).
  SparseViewOptions sparse_view;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
  InstanceMotionCheckOptions check_options() const;
  InstancePlacesOptions places_options() const { return {place_radius_m, place_memory_frames}; }
};

}  // namespace stillslam
