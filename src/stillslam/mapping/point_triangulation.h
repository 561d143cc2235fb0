#pragma once
// New map points from a keyframe and its best covisible neighbours: epipolar
// matches of unmatched keypoints are triangulated (two-view DLT when the rays'
// parallax beats the stereo parallax, else from the better stereo/depth
// measurement), then kept only if in front of both cameras, consistent with
// both observations (chi-square) and with the scale of both keypoints.
#include <functional>
#include <vector>

#include "stillslam/map/map.h"
#include "stillslam/map/triangulation_search.h"

namespace stillslam {

struct PointTriangulationOptions {
  std::size_t neighbours = 10;
  TriangulationSearchOptions search;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

// Holds the map's update mutex per neighbour. `should_stop` (may be empty) is
// polled between neighbours (new keyframe waiting). Appends new points to
// `recent`; returns their number.
int create_new_points(Map& map, KeyFrame& kf, std::vector<MapPointPtr>& recent,
                      const PointTriangulationOptions& options = {},
                      const std::function<bool()>& should_stop = {});

}  // namespace stillslam
