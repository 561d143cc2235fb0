#pragma once
// Duplicate fusion around a new keyframe (ORB-SLAM's SearchInNeighbors): its
// points are fused into its first- and second-order covisible keyframes and
// theirs into it; then descriptors, normals and covisibility are refreshed.
#include "stillslam/map/keyframe.h"

namespace stillslam {

struct FusionOptions {
  std::size_t neighbours = 10;
  std::size_t second_neighbours = 5;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

// Caller holds the map's update mutex. Returns fused/added observations.
int fuse_with_neighbours(KeyFrame& kf, const FusionOptions& options = {});

}  // namespace stillslam
