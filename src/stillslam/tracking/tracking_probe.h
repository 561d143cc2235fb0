#pragma once
// An opt-in observer of the tracker's stages, for diagnostics and benches
// (bench/bench_dynamic_points.cpp counts matches on moving objects with it).
// It sees the frame after each stage's pose optimization, outlier flags set,
// and is called with the map lock held; it must not change the frame or map.
#include <functional>

#include "stillslam/map/frame.h"
#include "stillslam/map/map.h"

namespace stillslam {

enum class TrackingStage {
  MotionModel,        // after the motion model's pose optimization
  ReferenceKeyFrame,  // after the reference keyframe's
  Lost,               // after the wide local-map search while lost (not relocalization)
  LocalMap,           // after the local map's (the frame's final pose)
  NewKeyFrame,        // after a keyframe was made of the frame (its new depth points set)
};

inline const char* to_string(TrackingStage stage) {
  switch (stage) {
    case TrackingStage::MotionModel: return "motion model";
    case TrackingStage::ReferenceKeyFrame: return "reference keyframe";
    case TrackingStage::Lost: return "lost";
    case TrackingStage::LocalMap: return "local map";
    case TrackingStage::NewKeyFrame: return "new keyframe";
  }
  return "?";
}

using TrackingProbe = std::function<void(TrackingStage, const Frame&, const Map&)>;

}  // namespace stillslam
