#pragma once
// Relocalization of a frame against candidate keyframes (ORB-SLAM's
// Relocalization, RGB-D/stereo): per candidate, match the frame's features to
// the keyframe's map points through the vocabulary's direct index, estimate
// the pose (3D-3D alignment in RANSAC when enough matches have depth, else
// PnP in RANSAC), optimize it, and when inliers are short, look for more
// matches by projecting the candidate's local map. The first candidate with
// enough inliers that also passes the verification wins.
//
// Verification (a false place match -- repeated texture, a similar corner of
// the room, the same photo on two walls -- can gather 50+ geometrically
// consistent inliers): with the pose, the candidate's local map (the keyframe
// and its best covisibles) is projected into the frame and searched once
// more. A prediction is checkable when the frame has a keypoint near it at a
// compatible scale; predictions onto areas without keypoints (a person masked
// out, blur, a blank wall) count neither way. The pose is accepted when
//  - at least min_found_ratio of the checkable predictions are pose inliers,
//  - and the inliers are spread like the predictions: of the image cells
//    (4 x 4) with enough checkable predictions, at least min_supported_cells
//    hold some inliers.
// At the true place the whole view is found (per point only a part: a map
// holds more points than one view re-detects); at a wrong place the inliers
// sit on the matched patch and the surroundings predicted around it are not
// found.
//
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
  // Verification (see the top of this file); min_found_ratio = 0 and
  // min_supported_cells = 0 disable it.
  double min_found_ratio = 0.15;
  int min_checked_points = 30;  // fewer checkable predictions: no point-ratio judgement
  double min_supported_cells = 0.6;
  int min_judged_cells = 4;       // fewer judged cells: no spread judgement
  int min_cell_predictions = 8;   // checkable predictions for a cell to be judged
  double min_cell_found_ratio = 0.1;  // a judged cell is supported with >= max(2, this x predictions) inliers
  // A prediction is checkable when a frame keypoint lies within this radius
  // (pixels at level 0, scaled with the predicted level) at a level +-1.
  float check_radius = 8.f;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

struct RelocalizationResult {
  bool success = false;
  Eigen::Isometry3d T_cam_world = Eigen::Isometry3d::Identity();
  KeyFramePtr keyframe;        // the candidate that relocalized the frame
  int inliers = 0;             // pose inliers of the best attempt
  int candidates_tried = 0;
  bool used_alignment = false;  // 3D-3D instead of PnP
  // Verification of the best attempt: checkable predictions of the local map
  // and how many of them are pose inliers (0 / 0 when not reached).
  int checked_points = 0;
  int found_points = 0;
  int judged_cells = 0;
  int supported_cells = 0;
  int rejected_by_verification = 0;  // candidates with enough inliers that failed it
};

class Relocalizer {
 public:
  explicit Relocalizer(RelocalizerOptions options = {}) : options_(options) { options_.check(); }

  // On success the frame holds the pose, its inlier map-point matches (outliers
  // cleared) and the winning keyframe as reference; on failure the frame's
  // matches are cleared and its pose is left as it was (none if it had none).
  RelocalizationResult relocalize(Frame& frame, const FeatureVector& frame_features,
                                  const std::vector<RelocalizationCandidate>& candidates) const;

  const RelocalizerOptions& options() const { return options_; }

 private:
  // Tries one candidate; the frame's matches are cleared on failure.
  RelocalizationResult try_candidate(Frame& frame, const FeatureVector& frame_features,
                                     const RelocalizationCandidate& candidate) const;
  // Guided search of the local map with the frame's pose, pose refinement,
  // then the found-ratio check; fills the result's inliers and check counts.
  bool verify(Frame& frame, const KeyFrame& kf, RelocalizationResult& result) const;

  RelocalizerOptions options_;
};

}  // namespace stillslam
