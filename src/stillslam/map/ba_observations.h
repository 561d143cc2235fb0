#pragma once
// Map -> bundle adjustment input shared by local BA (mapping/) and global BA
// (loop/): the observations of a map point by the keyframes in a problem.
#include <cstddef>
#include <unordered_map>
#include <vector>

#include "stillslam/features/scale_pyramid.h"
#include "stillslam/map/map_point.h"
#include "stillslam/optimize/bundle_adjustment.h"

namespace stillslam {

// The keyframes of a BA problem, each with its index in the problem's keyframe vector.
using BaKeyFrameIndex = std::unordered_map<const KeyFrame*, std::size_t>;

// Appends one BaObservation of BA point `point` per keyframe of `keyframes`
// that observes `mp` (in mp's observation order, keyframes elsewhere skipped);
// `keypoint_index`, if given, gets each observation's keypoint index.
// Returns how many were appended.
std::size_t append_ba_observations(const MapPoint& mp, std::size_t point, const BaKeyFrameIndex& keyframes,
                                   const ScalePyramid& pyramid, std::vector<BaObservation>& observations,
                                   std::vector<std::size_t>* keypoint_index = nullptr);

}  // namespace stillslam
