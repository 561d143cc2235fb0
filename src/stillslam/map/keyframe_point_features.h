#pragma once
// A keyframe's bag-of-words direct index restricted to the features that carry
// a live map point, with their descriptors gathered into one matrix (rows
// renumbered). Relocalization and loop detection both match against this.
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "stillslam/map/keyframe.h"
#include "stillslam/place/bow_vector.h"

namespace stillslam {

struct KeyframePointFeatures {
  cv::Mat descriptors;            // N x 32 CV_8U
  FeatureVector groups;           // direct index over the rows of `descriptors`
  std::vector<std::size_t> slot;  // row -> keyframe feature index
};

KeyframePointFeatures keyframe_point_features(const KeyFrame& kf, const FeatureVector& features);
// The same from a copy of the keyframe's slots taken under the map lock:
// feature i is kept when point_index[i] >= 0 (-1: no point or a bad one). It
// reads only descriptors, which a keyframe never changes after construction,
// so it runs without the lock.
KeyframePointFeatures keyframe_point_features(const KeyFrame& kf, const std::vector<std::int32_t>& point_index,
                                              const FeatureVector& features);

}  // namespace stillslam
