#pragma once
// Settings of the motion-aware dynamic handling (issue #19, `Motion.*`):
// segmented instances are judged by their motion (instance_motion_check.h)
// instead of by class alone. Off by default (see config/README.md).
#include "stillslam/tracking/instance_motion_check.h"
#include "stillslam/tracking/sparse_view.h"

namespace stillslam {

struct MotionOptions {
  bool enabled = false;
  // ORB features extracted inside the masked area (kept apart from tracking)
  // so masked instances can be judged too.
  int instance_features = 200;
  int span = 6;            // frames between the two views compared
  int person_frames = 10;  // agreeing frames a person needs before it is kept as static
  int default_frames = 10; // the same for every other class
  double min_iou = 0.3;    // mask overlap for an instance to keep its id across segmentations
  // The crowd fallback (Motion.sparseView*): the tracker's, with or without
  // `enabled` above (System copies it into TrackerOptions).
  SparseViewOptions sparse_view;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
  InstanceMotionCheckOptions check_options() const;
};

}  // namespace stillslam
