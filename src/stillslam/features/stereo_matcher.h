#pragma once
// Left-right feature matching for a rectified stereo pair (ORB-SLAM paper,
// section on stereo keypoints): for every left keypoint find the best right
// descriptor in the epipolar band and disparity range, refine by patch
// correlation on the keypoint's pyramid level (integer shift by zero-mean SAD,
// sub-pixel by a parabola through zero-mean SSD, which unlike a parabola
// through SAD is unbiased for locally linear images: 0.05 px vs 0.32 px mean
// error on the synthetic test pair), then reject outliers whose SAD is far
// above the median. Left keypoints still without a match try optical flow
// (stereo_flow.h).
#include <opencv2/core.hpp>
#include <vector>

#include "stillslam/features/orb_features.h"
#include "stillslam/features/scale_pyramid.h"
#include "stillslam/features/stereo_flow.h"
#include "stillslam/features/stereo_matches.h"

namespace stillslam {

struct StereoMatchOptions {
  int max_descriptor_distance = 75;  // Hamming; ORB-SLAM's (TH_HIGH + TH_LOW) / 2
  int patch_half_size = 5;           // patch window is (2w+1)^2 on the level image
  int search_window = 5;             // +- level pixels searched around the descriptor match
  float row_band = 2.f;              // epipolar band half-height at level 0, times scale[level]
  float min_disparity = 0.f;         // pixels at level 0
  float max_disparity = -1.f;        // pixels; < 0 means fx (depth >= baseline)
  float sad_outlier_factor = 2.1f;   // reject SAD > factor * median SAD (1.5 * 1.4)
  bool subpixel = true;              // parabola fit (false: integer SAD minimum only)
  // Left keypoints without a right keypoint get a match by optical flow
  // (stereo_flow.h). Settings: Stereo.flowMatching. Off by default: on the
  // generated halfsphere sequences it gave no gain (bench/README.md).
  bool flow_for_unmatched = false;
  StereoFlowOptions flow;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

// fx: rectified focal length (pixels); bf: baseline * fx (metres * pixels).
StereoMatches match_stereo(const OrbFeatures& left, const std::vector<cv::Mat>& left_pyramid,
                           const OrbFeatures& right, const std::vector<cv::Mat>& right_pyramid,
                           const ScalePyramid& pyramid, double fx, double bf,
                           const StereoMatchOptions& options = {});

// RGB-D: depth per keypoint read at the raw (distorted) keypoint position from
// a CV_32F depth image in metres (or CV_16U with `depth_scale` units per
// metre), and the virtual right coordinate u_r = u_undistorted - bf / depth.
// Invalid / non-positive depths give -1. `undistorted` may equal `raw`.
StereoMatches stereo_from_depth(const std::vector<cv::KeyPoint>& raw,
                                const std::vector<cv::KeyPoint>& undistorted,
                                const cv::Mat& depth, double bf, double depth_scale = 1.0);

}  // namespace stillslam
