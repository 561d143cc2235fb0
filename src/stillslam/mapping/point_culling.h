#pragma once
// Recent map point culling (ORB-SLAM): a new point must be found in at least
// a quarter of the frames that predicted it and, two keyframes after its
// creation, be observed by enough keyframes; after three keyframes it is
// trusted and leaves the recent list.
#include <cstdint>
#include <vector>

#include "stillslam/map/map_point.h"

namespace stillslam {

struct PointCullingOptions {
  double min_found_ratio = 0.25;
  int min_observations = 3;  // stereo/RGB-D observations count twice
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

// Returns the number of points set bad.
int cull_recent_points(std::vector<MapPointPtr>& recent, std::uint64_t current_keyframe_id,
                       const PointCullingOptions& options = {});

}  // namespace stillslam
