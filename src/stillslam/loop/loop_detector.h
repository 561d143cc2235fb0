#pragma once
// Loop detection for RGB-D/stereo maps (ORB-SLAM's DetectLoop + ComputeSim3
// with fixed scale):
//  1. candidates: keyframes resembling the query by bag of words, scoring at
//     least as well as its worst covisible neighbour, not connected to it;
//     grouped with their covisible neighbours (accumulated score) so a place
//     is judged by several keyframes, not one lucky image;
//  2. consistency: a candidate group must overlap a group found for the
//     previous keyframes, `consistency_threshold` keyframes in a row;
//  3. geometry: direct-index matches between the query's and the candidate's
//     map points, SE3 by 3D-3D alignment in RANSAC (depth unprojections),
//     guided search of the candidate's local map with the corrected pose and
//     a pose optimization that must keep enough inliers.
// Waiting for consecutive keyframes costs a loop that is only briefly
// revisited (keyframes come every ~20 degrees of a turn): as in ORB-SLAM3, a
// candidate that is not consistent yet is still verified, and accepted when
// the query's covisible keyframes, moved by the same correction, also see the
// loop's map points: keyframes in a row that found the candidate's group
// (the query included) + confirming neighbours >= consistency_threshold.
// The caller holds the map's update mutex for every call.
#include <Eigen/Geometry>
#include <optional>
#include <set>
#include <unordered_map>
#include <vector>

#include "stillslam/features/descriptor_matcher.h"
#include "stillslam/geometry/pnp.h"
#include "stillslam/loop/place_recognizer.h"
#include "stillslam/map/map.h"

namespace stillslam {

struct LoopDetectorOptions {
  // No detection until the map has this many keyframes, nor this many keyframe
  // ids after the last closed loop (ORB-SLAM: 10).
  int min_keyframes_between_loops = 10;
  // Consecutive keyframes whose candidate groups overlap (1 = no check).
  int consistency_threshold = 3;
  // A candidate's group: itself and its best covisible neighbours.
  std::size_t group_size = 10;
  // Keep groups whose accumulated score reaches this fraction of the best.
  double group_score_ratio = 0.75;
  int min_bow_matches = 20;
  DescriptorMatchOptions bow_matching{50, 0.75f, false};
  AlignmentRansacOptions alignment{300, 0.05, 0.995, 20, false, 7};
  float projection_window = 10.f;  // pixels at level 0
  int min_inliers = 40;            // after pose optimization on all matches
  // Covisible confirmation (0 = temporal consistency only): the query's best
  // covisible keyframes checked, and loop points a neighbour must match by
  // projection (ORB-SLAM3: 10 neighbours, 30 matches).
  std::size_t confirmation_neighbours = 10;
  int min_confirmation_matches = 30;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

// An accepted loop: the query keyframe seen from the loop keyframe's map.
struct LoopDetection {
  KeyFramePtr query;
  KeyFramePtr loop;  // the old keyframe that matched
  // The query's pose in the loop keyframe's (un-drifted) frame of the map.
  Eigen::Isometry3d T_world_query_corrected = Eigen::Isometry3d::Identity();
  // Per query keypoint: the loop-side map point it matched (inliers), or null.
  std::vector<MapPointPtr> matched_points;
  // The loop keyframe's and its covisibles' map points (to fuse).
  std::vector<MapPointPtr> loop_points;
  int inliers = 0;
  // Covisible keyframes of the query that confirmed the loop (0 when it was
  // accepted by temporal consistency without checking them).
  int confirmations = 0;
};

class LoopDetector {
 public:
  LoopDetector(const PlaceRecognizer& recognizer, LoopDetectorOptions options = {});

  // Steps 1-3 for one new keyframe (not yet in the recognizer, or already).
  std::optional<LoopDetection> detect(const Map& map, const KeyFrame& query);

  // Step 1: BoW candidates (group representatives, best first).
  std::vector<KeyFramePtr> candidates(const Map& map, const KeyFrame& query) const;
  // Step 2: updates the consistency state with this keyframe's candidates and
  // returns those consistent for long enough.
  std::vector<KeyFramePtr> consistent_candidates(const std::vector<KeyFramePtr>& candidates);
  // Step 3: the first candidate that passes the geometric checks.
  std::optional<LoopDetection> verify(const KeyFrame& query, const std::vector<KeyFramePtr>& candidates) const;
  // Step 3 for candidates that are not consistent yet: geometric checks, then
  // covisible confirmation (the first candidate that passes both). Uses the
  // consistency counts of the last consistent_candidates() call.
  std::optional<LoopDetection> verify_confirmed(const KeyFrame& query, const std::vector<KeyFramePtr>& candidates) const;
  // How many of the query's best covisible keyframes, moved by the detection's
  // correction, match at least min_confirmation_matches loop points.
  int count_confirmations(const LoopDetection& detection) const;

  // Called after a loop is closed: resets consistency and starts the gap.
  void loop_closed(std::uint64_t query_id);

 private:
  struct ConsistentGroup {
    std::set<std::uint64_t> keyframes;
    int count = 0;  // consecutive keyframes that found this group
  };
  std::optional<LoopDetection> verify_one(const KeyFrame& query, const BowDescription& query_words,
                                          const KeyFramePtr& candidate) const;

  const PlaceRecognizer& recognizer_;
  LoopDetectorOptions options_;
  std::vector<ConsistentGroup> groups_;
  // Keyframes in a row (this one included) that found each of this
  // keyframe's candidates' groups, from the last consistent_candidates().
  std::unordered_map<std::uint64_t, int> candidate_counts_;
  std::optional<std::uint64_t> last_loop_id_;
};

}  // namespace stillslam
