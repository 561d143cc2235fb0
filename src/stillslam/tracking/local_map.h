#pragma once
// The part of the map a frame is tracked against (ORB-SLAM's local map): the
// keyframes that see the frame's matched points, their best covisible
// neighbours, children and parents, and all points of those keyframes.
#include <vector>

#include "stillslam/map/frame.h"
#include "stillslam/map/keyframe.h"

namespace stillslam {

struct LocalMap {
  std::vector<KeyFrame*> keyframes;  // first = most shared points
  std::vector<MapPointPtr> points;   // unique, not bad
  KeyFrame* reference = nullptr;     // keyframe sharing most points with the frame
};

// From the keyframes observing the frame's matched points (seeds); when the
// frame has no matches, `fallback` (e.g. the last keyframe) seeds the map.
LocalMap build_local_map(const Frame& frame, KeyFrame* fallback, std::size_t max_keyframes = 80);

}  // namespace stillslam
