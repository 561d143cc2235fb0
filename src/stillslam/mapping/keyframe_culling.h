#pragma once
// Redundant keyframe culling (ORB-SLAM, stereo/RGB-D rule): a covisible
// keyframe of the new one is removed when more than 90% of its close map
// points are seen by at least three other keyframes at the same or a finer
// scale (pyramid level at most one above).
#include <vector>

#include "stillslam/map/map.h"

namespace stillslam {

struct KeyFrameCullingOptions {
  double redundancy = 0.9;
  int min_observers = 3;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

// Caller holds the map's update mutex. Returns the number of culled keyframes
// and, when culled_ids is given, appends their ids to it.
int cull_redundant_keyframes(Map& map, KeyFrame& kf, const KeyFrameCullingOptions& options = {},
                             std::vector<std::uint64_t>* culled_ids = nullptr);

// Fraction of a keyframe's close points that are redundant by the rule above
// (exposed for tests and diagnostics).
double keyframe_redundancy(const KeyFrame& kf, const KeyFrameCullingOptions& options = {});

}  // namespace stillslam
