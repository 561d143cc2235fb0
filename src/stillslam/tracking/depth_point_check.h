#pragma once
// The two-frame check of new depth points (issue #20): a keyframe's keypoint
// becomes a map point from its depth only when the previous frame saw the same
// 3D point where the camera motion alone puts it. Something that moved
// between the two frames (a person the segmentation missed) is not where the
// camera motion predicts and is not made a map point; a static point usually
// is. Geometry only, so it applies with and without segmentation.
#include <cstdint>

#include "stillslam/map/frame.h"

namespace stillslam {

struct DepthPointCheckOptions {
  // Tracking.newPointCheck. Off by default: on the issue #20 renders it cut the
  // moving points the map takes in by 73 % but did not stop tracking from
  // following a close person, and it cost static / segmentation-on accuracy
  // on some sequences (1.06-1.20x, bench/README.md).
  bool enabled = false;
  float radius = 4.f;             // Tracking.newPointCheckRadius: search window in the previous frame, px at level 0
  int max_descriptor_distance = 100;  // guided matching's HIGH threshold
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

// Whether `previous` (with a pose) has a keypoint within the window around
// the projection of `point_world` whose descriptor is within the threshold and
// whose stereo/RGB-D observation (u, v, u_right) explains the point within
// the 95 % chi-square bound of its pyramid level.
bool seen_where_predicted(const Frame& previous, const Eigen::Vector3d& point_world, const std::uint8_t* descriptor,
                          const DepthPointCheckOptions& options);

}  // namespace stillslam
