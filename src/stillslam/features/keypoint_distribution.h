#pragma once
// Even spatial distribution of keypoints with a quadtree (ORB-SLAM): the
// region is split into nodes breadth first (shallower nodes first, then the
// most populated) until there are at least `target` non-empty nodes or no
// node holds more than one keypoint; each node keeps its strongest keypoint.
// Equal-area nodes make the result uniform in space, not proportional to the
// local corner density.
#include <opencv2/core.hpp>
#include <vector>

namespace stillslam {

// Returns indices into `keypoints` (ascending) of at most `target` keypoints;
// if the last split round overshoots, the weakest node winners are dropped.
// Keypoints outside `region` are ignored.
std::vector<std::size_t> distribute_quadtree(const std::vector<cv::KeyPoint>& keypoints,
                                             const cv::Rect2f& region, int target);

}  // namespace stillslam
