#pragma once
// Duplicate fusion (ORB-SLAM's Fuse): projects map points into a keyframe;
// when a keypoint there matches (reprojection chi-square and descriptor
// distance), the point either gains that observation or is merged with the
// point already in the slot (the one with more observations survives).
#include <vector>

#include "stillslam/map/keyframe.h"

namespace stillslam {

// Returns the number of fused or added observations.
int fuse(KeyFrame& keyframe, const std::vector<MapPointPtr>& points, float th = 3.0f);

}  // namespace stillslam
