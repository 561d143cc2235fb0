#pragma once
// First step of local mapping for a new keyframe: the map points tracking
// matched in it get the keyframe as an observation (updating their normal,
// distances and descriptor), points the keyframe created itself are returned
// as "recent" (to be checked by culling), and its covisibility edges are built.
#include <vector>

#include "stillslam/map/keyframe.h"

namespace stillslam {

// Appends the keyframe's freshly created points to `recent`.
void register_keyframe(KeyFrame& kf, std::vector<MapPointPtr>& recent);

}  // namespace stillslam
