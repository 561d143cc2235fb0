#pragma once
// What the dynamic filter did to one frame, for display (publish layer):
// kept apart from FrameBuildStats, which is copied into every frame's stats.
#include <opencv2/core.hpp>

#include <vector>

#include "stillslam/segmentation/detection.h"

namespace stillslam {

struct FrameDynamics {
  std::vector<Detection> detections;           // all classes, frame pixels (masks shared, not copied)
  std::vector<cv::Point2f> removed_keypoints;  // features the dynamic mask removed, level-0 pixels
};

}  // namespace stillslam
