#pragma once
// A 3D landmark observed by keyframes.
//
// Threading: map points, keyframes and the Map are NOT internally
// synchronized. Every read or write of map structure happens while holding
// Map::update_mutex() (tracking holds it for the map-facing part of a frame,
// local mapping for each structural step); see map.h.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <opencv2/core.hpp>

#include "stillslam/map/keyframe_order.h"

namespace stillslam {

class KeyFrame;
struct ScalePyramid;

class MapPoint : public std::enable_shared_from_this<MapPoint> {
 public:
  using Observations = std::map<KeyFrame*, std::size_t, KeyFrameIdLess>;

  // `reference` is the keyframe that created the point (non-owning).
  MapPoint(std::uint64_t id, const Eigen::Vector3d& position_world, KeyFrame* reference);

  std::uint64_t id() const { return id_; }
  std::uint64_t first_keyframe_id() const { return first_keyframe_id_; }
  const Eigen::Vector3d& position() const { return position_; }
  void set_position(const Eigen::Vector3d& p) { position_ = p; }
  // Mean viewing direction (unit) from the observing keyframes.
  const Eigen::Vector3d& normal() const { return normal_; }
  // Representative descriptor (32 bytes).
  const std::uint8_t* descriptor() const { return descriptor_.data(); }
  // For points without observations (tracking's temporary odometry points).
  void set_descriptor(const std::uint8_t* d) {
    std::copy(d, d + descriptor_.size(), descriptor_.begin());
    descriptor_from_ = -1;
  }
  // Scale-invariance distance range (ORB-SLAM: the point can be matched when
  // seen from a distance inside [min, max]).
  double min_distance() const { return 0.8 * min_distance_; }
  double max_distance() const { return 1.2 * max_distance_; }
  // Pyramid level at which the point should appear when seen from `distance`.
  int predict_level(double distance, const ScalePyramid& pyramid) const;
  // The unscaled far end of the range, predict_level's reference (copies of a
  // point taken under the map lock use it with predict_scale_level).
  double level_reference_distance() const { return max_distance_; }

  // Observations: keyframe -> keypoint index. Stereo/RGB-D observations count
  // twice in num_observations() (as ORB-SLAM), mono ones once.
  const Observations& observations() const { return observations_; }
  int num_observations() const { return num_observations_; }
  bool is_observed_by(const KeyFrame* kf) const { return observations_.find(kf) != observations_.end(); }
  std::ptrdiff_t index_in(const KeyFrame* kf) const;
  void add_observation(KeyFrame* kf, std::size_t index);
  // Removes the observation; the point turns bad with <= 2 observations left.
  void erase_observation(KeyFrame* kf);

  // Tracking statistics: visible = predicted in a frame's frustum, found =
  // actually matched there.
  void increase_visible(int n = 1) { visible_ += n; }
  void increase_found(int n = 1) { found_ += n; }
  double found_ratio() const { return visible_ > 0 ? static_cast<double>(found_) / visible_ : 0.0; }
  // Consecutive tracked frames in which the point was matched but rejected as
  // an outlier by the pose optimization (an inlier match resets it).
  int outlier_streak() const { return outlier_streak_; }
  void record_tracking_match(bool inlier) { outlier_streak_ = inlier ? 0 : outlier_streak_ + 1; }
  // The last frame whose final pose rejected the point (none yet: nullopt).
  std::optional<std::uint64_t> last_outlier_frame() const { return last_outlier_frame_; }
  void record_outlier_frame(std::uint64_t frame_id) { last_outlier_frame_ = frame_id; }
  int visible() const { return visible_; }
  int found() const { return found_; }
  // Seen on an instance of a dynamic class (a person) that the motion check
  // kept as static (tracking/motion_stage.h): it may track, but it is never
  // saved with the map, so maps for localization hold no people.
  bool on_dynamic_instance() const { return on_dynamic_instance_; }
  void mark_on_dynamic_instance() { on_dynamic_instance_ = true; }
  // The frame of the newest keyframe that matched this point but waits for
  // its frame's own mask before local mapping registers the observation
  // (tracking/keyframe_hold.h with Segmentation.heldEvidence); 0: none. The
  // static-evidence span (tracking/static_evidence.h) counts it as an
  // observation. Set and read under Map::update_mutex().
  std::uint64_t held_observation_frame() const { return held_observation_frame_; }
  void note_held_observation(std::uint64_t frame_id) {
    held_observation_frame_ = std::max(held_observation_frame_, frame_id);
  }
  void clear_held_observation() { held_observation_frame_ = 0; }

  // Recomputes the representative descriptor: the observation descriptor with
  // the least median Hamming distance to all others. Returns at once when the
  // observations (and which of their keyframes are bad) are those of the last
  // computation.
  void compute_distinctive_descriptor();
  // Recomputes normal and min/max distances from the observations.
  void update_normal_and_depth(const ScalePyramid& pyramid);

  // Made by a keyframe under a carried mask (Segmentation.provisionalPoints,
  // tracking/provisional_points.h): out of tracking, local and global BA,
  // fusion and culling until that frame's own mask confirms it or culls it.
  // Set and read under Map::update_mutex(), like everything here.
  bool is_provisional() const { return provisional_; }
  void set_provisional() { provisional_ = true; }
  // An ordinary point from now on; culling counts its age from keyframe
  // `next_keyframe_id` (the next one made), not from its first keyframe.
  void confirm(std::uint64_t next_keyframe_id) {
    provisional_ = false;
    culling_start_keyframe_id_ = next_keyframe_id;
  }
  // The keyframe id point culling counts a recent point's age from.
  std::uint64_t culling_start_keyframe_id() const { return culling_start_keyframe_id_; }

  bool is_bad() const { return bad_; }
  // Removes the point from all observing keyframes.
  void set_bad();
  // Moves all observations to `other` (duplicate fusion); this point becomes bad.
  void replace_with(const std::shared_ptr<MapPoint>& other);
  // The point this one was fused into (follow the chain), or nullptr.
  std::shared_ptr<MapPoint> replaced_by() const { return replaced_by_; }

 private:
  friend struct MapFileAccess;  // map_file.cpp saves and restores every field (normal, distances, reference)
  std::uint64_t id_;
  std::uint64_t first_keyframe_id_;
  std::uint64_t culling_start_keyframe_id_;
  Eigen::Vector3d position_;
  Eigen::Vector3d normal_ = Eigen::Vector3d::Zero();
  std::array<std::uint8_t, 32> descriptor_{};
  // Observation descriptors (of keyframes not bad) descriptor_ was computed
  // from; -1 after any change of the observations or of descriptor_.
  // Keyframes never stop being bad, so with unchanged observations the same
  // count means the same descriptors.
  int descriptor_from_ = -1;
  double min_distance_ = 0, max_distance_ = 0;
  Observations observations_;
  int num_observations_ = 0;
  KeyFrame* reference_;
  int visible_ = 1, found_ = 1;
  int outlier_streak_ = 0;  // not saved in map files: a tracking statistic like the two above
  std::optional<std::uint64_t> last_outlier_frame_;  // nor this one
  std::uint64_t held_observation_frame_ = 0;          // nor this one
  bool on_dynamic_instance_ = false;  // such points are left out of map files
  bool provisional_ = false;  // not saved in map files: maps are saved after the last check
  bool bad_ = false;
  std::shared_ptr<MapPoint> replaced_by_;
};

using MapPointPtr = std::shared_ptr<MapPoint>;

// MapPoint::predict_level for a point whose level_reference_distance() is
// `reference_distance`.
int predict_scale_level(double reference_distance, double distance, const ScalePyramid& pyramid);

}  // namespace stillslam
