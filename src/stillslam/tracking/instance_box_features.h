#pragma once
// The motion stage's features inside masked instances (motion_stage.h),
// extracted on each instance's bounding box instead of the whole pyramid:
// the masks cover a fraction of the view, so most of a full-frame pass was
// spent on pixels whose corners are thrown away.
#include <opencv2/core.hpp>

#include <vector>

#include "stillslam/features/orb_features.h"
#include "stillslam/features/orb_options.h"

namespace stillslam {

// Each box grown by `pad` pixels and clipped to `image`; boxes that then
// overlap are merged, so no pixel is extracted twice. Empty boxes are dropped.
std::vector<cv::Rect> merge_instance_boxes(const std::vector<cv::Rect>& boxes, int pad, cv::Size image);

// ORB features of `gray` inside `boxes` (merge_instance_boxes' output) on
// pixels where `inside` is non-zero, in full-image pixels. `orb`'s settings
// with `budget` features shared by the boxes in proportion to their area, each
// box getting at least half an equal share (the total can exceed `budget`
// by up to half); a
// box gets the pyramid levels whose image is still larger than the ORB patch
// border on both sides (one level at least).
OrbFeatures extract_in_boxes(const OrbOptions& orb, int budget, const cv::Mat& gray, const cv::Mat1b& inside,
                             const std::vector<cv::Rect>& boxes);

}  // namespace stillslam
