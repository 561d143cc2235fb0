#pragma once
// Relocalization of a frame against candidate keyframes (ORB-SLAM's
// Relocalization, RGB-D/stereo): per candidate, match the frame's features to
// the keyframe's map points through the vocabulary's direct index, estimate
// the pose (3D-3D alignment in RANSAC when enough matches have depth, else
// PnP in RANSAC), optimize it, and when inliers are short, look for more
// matches by projecting the candidate's local map. The first candidate with
// enough inliers wins.
//
// Candidates come from place recognition (loop/place_recognizer.h); this file
// only needs their keyframes and direct indexes, so tracking does not depend
// on loop/. The caller holds the map's update mutex.
#include <Eigen/Geometry>
#include <vector>

#include "stillslam/features/descriptor_matcher.h"
#include "stillslam/geometry/pnp.h"
#include "stillslam/map/frame.h"
#include "stillslam/map/keyframe.h"
#include "stillslam/place/bow_vector.h"

namespace stillslam {

struct RelocalizationCandidate {
  KeyFramePtr keyframe;
  FeatureVector features;  // the keyframe's direct index (same vocabulary and level as the frame's)
};

struct RelocalizerOptions {
  int min_bow_matches = 15;     // per candidate, before any geometry
  int min_inliers = 50;         // accept with at least this many pose inliers
  int min_ransac_inliers = 10;  // consensus needed to continue with a candidate
  DescriptorMatchOptions bow_matching{50, 0.75f, false};
  PnpRansacOptions pnp{300, 2.5, 0.99, 10, true};
  AlignmentRansacOptions alignment{300, 0.05, 0.995, 10, false, 7};
  // Use 3D-3D alignment when at least this fraction of the matches has depth.
  double min_depth_fraction = 0.5;
  // Guided search windows (pixels at level 0) of the two projection rounds.
  float coarse_window = 10.f;
  float fine_window = 3.f;
};

struct RelocalizationResult {
  bool success = false;
  Eigen::Isometry3d T_cam_world = Eigen::Isometry3d::Identity();
  KeyFramePtr keyframe;        // the candidate that relocalized the frame
  int inliers = 0;             // pose inliers of the best attempt
  int candidates_tried = 0;
  bool used_alignment = false;  // 3D-3D instead of PnP
};

class Relocalizer {
 public:
  explicit Relocalizer(RelocalizerOptions options = {}) : options_(options) {}

  // On success the frame holds the pose, its inlier map-point matches (outliers
  // cleared) and the winning keyframe as reference; on failure the frame's
  // matches are cleared and its pose is left untouched.
  RelocalizationResult relocalize(Frame& frame, const FeatureVector& frame_features,
                                  const std::vector<RelocalizationCandidate>& candidates) const;

  const RelocalizerOptions& options() const { return options_; }

 private:
  // Tries one candidate; the frame's matches are cleared on failure.
  RelocalizationResult try_candidate(Frame& frame, const FeatureVector& frame_features,
                                     const RelocalizationCandidate& candidate) const;

  RelocalizerOptions options_;
};

}  // namespace stillslam
