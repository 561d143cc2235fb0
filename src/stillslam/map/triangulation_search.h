#pragma once
// Matches between two keyframes' unmatched keypoints for triangulating new
// map points (ORB-SLAM's SearchForTriangulation, without a vocabulary): each
// keypoint of kf1 is searched along its epipolar segment in kf2 — the short
// segment around its measured depth when it has one, else the whole ray —
// using kf2's feature grid; candidates must be near the epipolar line (within
// the keypoint level's sigma), close in descriptor space and rotation-consistent.
#include <cstddef>
#include <utility>
#include <vector>

#include "stillslam/map/keyframe.h"

namespace stillslam {

struct TriangulationSearchOptions {
  double min_depth = 0.1;      // metres, near end of the ray for keypoints without depth
  double max_depth = 80.0;     // metres, far end
  double depth_margin = 0.25;  // relative depth interval around a measured depth
  float window = 6.0f;         // search half-window (pixels at level 0, times level scale)
  bool check_orientation = true;
};

// Pairs (index in kf1, index in kf2); each index used once.
std::vector<std::pair<std::size_t, std::size_t>> search_for_triangulation(
    const KeyFrame& kf1, const KeyFrame& kf2, const TriangulationSearchOptions& options = {});

}  // namespace stillslam
