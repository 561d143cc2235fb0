#pragma once
// The segmenter's detections as the publish layer shows them: box, class,
// score and the outline of the instance mask (no mask is copied).
#include <vector>

#include "stillslam/publish/snapshots.h"
#include "stillslam/segmentation/detection.h"

namespace stillslam {

// dynamic_class_ids: the classes whose pixels were masked (unordered, small).
std::vector<FrameSnapshot::Instance> snapshot_instances(const std::vector<Detection>& detections,
                                                        const std::vector<int>& dynamic_class_ids);

}  // namespace stillslam
