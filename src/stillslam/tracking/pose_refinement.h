#pragma once
// Motion-only BA of a frame against its matched map points: builds the
// observations (stereo/RGB-D ones with the virtual right coordinate), runs
// optimize_pose and writes back the pose and per-keypoint outlier flags.
#include <vector>

#include "stillslam/map/frame.h"
#include "stillslam/optimize/pose_optimizer.h"

namespace stillslam {

// Keypoint i of the frame against its matched map point (which must be set),
// weighted by the keypoint's pyramid level.
PoseObservation pose_observation(const Frame& frame, std::size_t i);
// The observations of the frame's matched map points not marked outliers.
std::vector<PoseObservation> inlier_observations(const Frame& frame);

// Returns the number of inlier observations. The frame must have a pose.
// A prior (optimize/pose_prior.h) joins the optimization when given.
int refine_pose(Frame& frame, const PoseOptimizerOptions& options = {}, const PosePrior* prior = nullptr);

// Clears the slots of outlier matches (they are not map observations of this
// frame) and returns how many inliers are real map points (>= 1 observation).
int discard_outliers(Frame& frame);

}  // namespace stillslam
