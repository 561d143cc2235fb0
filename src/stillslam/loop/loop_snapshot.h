#pragma once
// What loop verification reads of the map, copied under the map lock by
// LoopDetector::prepare so that LoopDetector::verify runs without it
// (loop_detector.h). Poses, map-point slots and map points change under other
// threads (local BA, culling, fusion) and are copied; a keyframe's features
// (keypoints, descriptors, depth, u_right, grid, setup) never change after
// construction (map/keyframe.h) and are read through the KeyFramePtr.
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "stillslam/loop/place_recognizer.h"
#include "stillslam/map/keyframe.h"
#include "stillslam/map/map_point.h"

namespace stillslam {

// A map point as alignment and projection matching read it.
struct PointCopy {
  MapPointPtr point;  // handed on in the detection; verification never dereferences it
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  std::array<std::uint8_t, 32> descriptor{};
  double min_distance = 0, max_distance = 0;  // MapPoint::min_distance() / max_distance()
  double level_reference_distance = 0;        // for predict_scale_level
};

// A keyframe's pose and map-point slots when the snapshot was taken.
struct KeyFrameCopy {
  KeyFramePtr keyframe;  // its features are read through it
  Eigen::Isometry3d T_cam_world = Eigen::Isometry3d::Identity();
  // Per keypoint: index into LoopSnapshot::points of its map point, -1 for
  // none or a bad one. Empty for confirmation neighbours (pose only).
  std::vector<std::int32_t> point_index;
};

// One candidate, in the order verification tries them.
struct LoopCandidateCopy {
  KeyFrameCopy keyframe;
  std::shared_ptr<const BowDescription> words;  // null: not indexed (rejected)
  // The candidate's and its non-bad covisible keyframes' non-bad points,
  // first seen first (indices into LoopSnapshot::points): the loop points.
  std::vector<std::int32_t> loop_points;
  // false: accepted on geometry alone (temporally consistent); true: also
  // needs this many confirming covisible keyframes of the query.
  bool needs_confirmation = false;
  int needed_confirmations = 0;
};

struct LoopSnapshot {
  KeyFrameCopy query;
  std::shared_ptr<const BowDescription> query_words;
  // The query's best covisible keyframes that were not bad (best first), for
  // covisible confirmation; empty when no candidate needs it.
  std::vector<KeyFrameCopy> neighbours;
  std::vector<LoopCandidateCopy> candidates;
  std::vector<PointCopy> points;  // each map point once
};

// Fills a LoopSnapshot; the caller holds the map lock throughout.
class LoopSnapshotBuilder {
 public:
  LoopSnapshotBuilder(const KeyFrame& query, std::shared_ptr<const BowDescription> query_words,
                      std::size_t confirmation_neighbours);
  // `words`: the candidate's stored description (null if not indexed). Bad
  // candidates are left out (verification would reject them).
  void add_candidate(const KeyFramePtr& candidate, std::shared_ptr<const BowDescription> words,
                     bool needs_confirmation = false, int needed_confirmations = 0);
  bool empty() const { return snapshot_.candidates.empty(); }
  LoopSnapshot take() { return std::move(snapshot_); }

 private:
  std::int32_t point(const MapPointPtr& mp);  // its index, copied on first use
  KeyFrameCopy copy_keyframe(const KeyFrame& kf, bool with_points);

  LoopSnapshot snapshot_;
  std::size_t confirmation_neighbours_;
  bool neighbours_copied_ = false;
  std::unordered_map<const MapPoint*, std::int32_t> index_;
  std::vector<std::size_t> last_seen_by_;  // per point: 1 + candidate that last collected it
};

}  // namespace stillslam
