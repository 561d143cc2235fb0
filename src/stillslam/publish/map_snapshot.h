#pragma once
// Builds the snapshot of one map. The caller holds the map's update mutex
// (the tracking thread does, at the end of a frame).
#include "stillslam/map/map.h"
#include "stillslam/publish/snapshots.h"

namespace stillslam {

// Active keyframes and good points of `map`, covisibility edges of at least
// `min_covisibility_weight` shared points (each once). The trajectory is left
// to the caller (frames are not part of the map).
MapSnapshot snapshot_map(const Map& map, int min_covisibility_weight);

}  // namespace stillslam
