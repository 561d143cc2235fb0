#pragma once
// New depth points near a carried person (async segmentation). A mask
// carried from an older segmentation misses the parts of a person that moved
// differently from the rest (an arm, a leg): they lie next to the carried
// instance, at about its depth. The background seen beside or behind the
// person is farther. So when a keyframe is made under a carried mask, a
// keypoint within a radius of a carried instance (growing with the mask's
// age) whose depth is within a band of that instance's median depth makes no
// new depth point; other keypoints are unaffected. Geometry and the carried
// masks only; nothing happens at mask age 0 or without carried instances.
#include <vector>

#include "stillslam/map/frame.h"

namespace stillslam {

struct NearPersonOptions {
  // Segmentation.nearPersonPxPerFrame: the radius around a carried instance,
  // pixels per processed frame of mask age. 0: off.
  double px_per_frame = 0;
  // Segmentation.nearPersonMaxPx: the radius's cap (pixels).
  int max_px = 40;
  // Segmentation.nearPersonDepthBand: a keypoint within the radius is taken
  // to be on the person when its depth differs from the instance's median
  // depth by at most this (metres).
  double depth_band_m = 0.5;
  // Segmentation.nearPersonAtStart: the rule applies to the map's first
  // keyframe too (0: that keyframe keeps every depth point the start check
  // kept; a map started among people then has its static points next to them).
  bool at_start = true;
  bool enabled() const { return px_per_frame > 0; }
  double radius_px(int mask_age) const;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

// Per keypoint of `frame` (by index): 1 when it has a depth and lies within
// options.radius_px(frame.mask_age()) pixels (its detected position, the
// masks' pixels) of a carried instance whose median depth is known and
// within depth_band_m of its own. All 0 when the option is off, the mask age
// is <= 0 or the frame has no carried instances.
std::vector<char> near_carried_person(const Frame& frame, const NearPersonOptions& options);

}  // namespace stillslam
