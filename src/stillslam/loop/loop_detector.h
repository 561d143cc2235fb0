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
//
// Lock contract (the map's update mutex), so that the expensive step 3 does
// not stall tracking:
//   prepare  (lock held, cheap): steps 1-2 and a LoopSnapshot of everything
//            step 3 reads that other threads may change (loop_snapshot.h);
//   verify   (no lock): step 3 on the snapshot alone;
//   recheck  (lock held again): drops what turned bad meanwhile.
// detect() runs the three in a row; every other call needs the lock.
#include <Eigen/Geometry>
#include <optional>
#include <set>
#include <unordered_map>
#include <vector>

#include "stillslam/features/descriptor_matcher.h"
#include "stillslam/geometry/pnp.h"
#include "stillslam/loop/loop_snapshot.h"
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

  // prepare + verify + recheck for one new keyframe (not yet in the
  // recognizer, or already); the caller holds the lock.
  std::optional<LoopDetection> detect(const Map& map, const KeyFrame& query);

  // Steps 1-2 (updates the consistency state) and the snapshot of the
  // candidates to verify: the consistent ones, then, with covisible
  // confirmation, the others. nullopt: nothing to verify (too early after the
  // last loop, no candidate, or none consistent without confirmation).
  // Caller holds the lock.
  std::optional<LoopSnapshot> prepare(const Map& map, const KeyFrame& query);
  // Step 3 on a snapshot: the first candidate that passes the geometric checks
  // (and covisible confirmation where it needs it). No lock needed; does not
  // touch the detector's state, so it may run on another thread than prepare.
  std::optional<LoopDetection> verify(const LoopSnapshot& snapshot) const;
  // A verified detection against the map as it is now: nullopt if the query
  // or loop keyframe turned bad or the loop keyframe left `map`; matched and
  // loop points that turned bad are dropped, and the remaining matches must
  // still be min_inliers (`inliers` becomes their count). Caller holds the lock.
  std::optional<LoopDetection> recheck(const Map& map, LoopDetection detection) const;

  // Step 1: BoW candidates (group representatives, best first).
  std::vector<KeyFramePtr> candidates(const Map& map, const KeyFrame& query) const;
  // Step 2: updates the consistency state with this keyframe's candidates and
  // returns those consistent for long enough.
  std::vector<KeyFramePtr> consistent_candidates(const std::vector<KeyFramePtr>& candidates);
  // Step 3 with the lock held: the first candidate that passes the geometric
  // checks (no confirmation).
  std::optional<LoopDetection> verify(const KeyFrame& query, const std::vector<KeyFramePtr>& candidates) const;

  // Called after a loop is closed: resets consistency and starts the gap.
  void loop_closed(std::uint64_t query_id);

 private:
  struct ConsistentGroup {
    std::set<std::uint64_t> keyframes;
    int count = 0;  // consecutive keyframes that found this group
  };
  std::shared_ptr<const BowDescription> words_of(const KeyFrame& query) const;
  std::vector<KeyFramePtr> candidates(const Map& map, const KeyFrame& query, const BowVector& bow) const;

  const PlaceRecognizer& recognizer_;
  LoopDetectorOptions options_;
  std::vector<ConsistentGroup> groups_;
  // Keyframes in a row (this one included) that found each of this
  // keyframe's candidates' groups, from the last consistent_candidates().
  std::unordered_map<std::uint64_t, int> candidate_counts_;
  std::optional<std::uint64_t> last_loop_id_;
};

}  // namespace stillslam
