#pragma once
// Where to look in the right image for left keypoints that found no right
// keypoint: pyramidal Lucas-Kanade flow from the left to the right image (as
// VINS-Fusion and OpenVINS track stereo), started at the disparity of the
// nearest matched keypoints, kept only when the flow back lands on the
// keypoint and the match stays on its row. ORB's right keypoints miss about
// half of the left ones (other corners win the quadtree), and with a dynamic
// mask the left budget is spent on the static part while the right one is not.
// The proposal is then refined like a descriptor match (stereo_matcher.cpp),
// so every stereo depth comes from the same zero-mean patch fit.
#include <opencv2/core.hpp>
#include <vector>

#include "stillslam/features/orb_features.h"

namespace stillslam {

struct StereoFlowOptions {
  int window = 21;             // LK window (pixels, level 0)
  int pyramid_levels = 1;      // LK levels above level 0 (the start is already close)
  int guess_neighbours = 5;    // matched keypoints whose median disparity starts the flow
  float max_row_offset = 1.f;  // |v_right - v_left| on a rectified pair (pixels)
  float max_round_trip = 0.5f; // forward-backward flow error (pixels)
};

// For each left keypoint with u_right[i] < 0: the proposed right column
// (level-0 pixels), or -1. Keypoints that already have a match get -1. Needs
// matched keypoints to start from; with none it proposes nothing. The right
// image is scaled to the left one's mean and contrast first, since LK compares
// raw intensities and the two cameras' exposures differ.
std::vector<float> flow_right_proposals(const OrbFeatures& left, const std::vector<float>& u_right,
                                        const cv::Mat& left_image, const cv::Mat& right_image,
                                        const StereoFlowOptions& options);

}  // namespace stillslam
