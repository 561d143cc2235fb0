#pragma once
// Place recognition across the maps of an atlas: is a keyframe of the active
// map a place some other map has seen? The same three steps as loop
// detection (loop_detector.h: BoW candidates grouped by covisibility,
// consistency over several consecutive keyframes, SE3 by 3D-3D RANSAC with
// guided search and a pose check), with the candidates taken from one other
// map (the shared keyframe database holds every map; Map::keyframe filters
// it). Consistency is tracked per other map. The caller holds the active
// map's and the other map's update mutexes for every call.
#include <cstdint>
#include <map>
#include <optional>

#include "stillslam/loop/loop_detector.h"
#include "stillslam/loop/place_recognizer.h"
#include "stillslam/map/map.h"

namespace stillslam {

class MergeDetector {
 public:
  MergeDetector(const PlaceRecognizer& recognizer, LoopDetectorOptions options = {});

  // Looks for `query` (a keyframe of another map) in `other`. The detection's
  // T_world_query_corrected is the query's pose in `other`'s frame.
  std::optional<LoopDetection> detect(const Map& other, const KeyFrame& query);
  // The geometric check alone, against one keyframe (re-checks a detection
  // after local mapping has been stopped).
  std::optional<LoopDetection> verify(const KeyFrame& query, const KeyFramePtr& candidate) const;
  // Forgets the consistency state (after a merge or when a new map starts).
  void reset() { detectors_.clear(); }

 private:
  const PlaceRecognizer& recognizer_;
  LoopDetectorOptions options_;
  LoopDetector verifier_;
  std::map<std::uint64_t, LoopDetector> detectors_;  // per other map id
};

}  // namespace stillslam
