#pragma once
// A keyframe: a frame kept in the map, with its features, the map points it
// observes, its covisibility edges (weight = number of shared map points) and
// its place in the spanning tree. Not internally synchronized (see map_point.h).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <set>
#include <vector>

#include "stillslam/features/feature_grid.h"
#include "stillslam/map/camera_setup.h"
#include "stillslam/map/keyframe_order.h"
#include "stillslam/map/map_point.h"

namespace stillslam {

class Frame;

class KeyFrame : public std::enable_shared_from_this<KeyFrame> {
 public:
  // Copies features, pose and map-point slots of a posed frame.
  KeyFrame(std::uint64_t id, const Frame& frame);

  std::uint64_t id() const { return id_; }
  std::uint64_t frame_id() const { return frame_id_; }
  double timestamp() const { return timestamp_; }
  const CameraSetup& setup() const { return *setup_; }

  // Pose.
  const Eigen::Isometry3d& T_cam_world() const { return T_cam_world_; }
  // The inverse is kept with the pose: mapping asks for camera centres far
  // more often than poses change.
  Eigen::Isometry3d T_world_cam() const { return T_world_cam_; }
  Eigen::Vector3d camera_center() const { return T_world_cam_.translation(); }
  void set_pose(const Eigen::Isometry3d& T_cam_world) {
    T_cam_world_ = T_cam_world;
    T_world_cam_ = T_cam_world.inverse();
  }
  // For a culled keyframe, its pose through the spanning tree (the parent's
  // current pose and the relative pose at culling time); else the pose.
  Eigen::Isometry3d T_cam_world_resolved() const;

  // Features (undistorted keypoints). Keypoints, descriptors, u_right, depth,
  // the feature grid and the setup are set by the constructor and never
  // change: no member writes them and there is no setter (the descriptor
  // matrix shares its data with the Frame's, which has no setter either). Code
  // holding a KeyFramePtr may read them without the map lock
  // (loop/loop_snapshot.h relies on it); everything else needs the lock.
  std::size_t size() const { return keypoints_.size(); }
  const cv::KeyPoint& keypoint(std::size_t i) const { return keypoints_[i]; }
  const std::uint8_t* descriptor(std::size_t i) const { return descriptors_.ptr<std::uint8_t>(static_cast<int>(i)); }
  float u_right(std::size_t i) const { return u_right_[i]; }
  float depth(std::size_t i) const { return depth_[i]; }
  // World point of a keypoint with depth.
  std::optional<Eigen::Vector3d> unproject(std::size_t i) const;
  std::vector<std::size_t> features_in_area(float x, float y, float r, int min_level = -1,
                                            int max_level = -1) const {
    return grid_->features_in_area(x, y, r, min_level, max_level);
  }

  // Map-point slots.
  const MapPointPtr& map_point(std::size_t i) const { return map_points_[i]; }
  const std::vector<MapPointPtr>& map_points() const { return map_points_; }
  void set_map_point(std::size_t i, MapPointPtr mp) { map_points_[i] = std::move(mp); }
  void erase_map_point(std::size_t i) { map_points_[i].reset(); }
  // Non-bad points with at least `min_observations` observations.
  int num_tracked_points(int min_observations) const;

  // Covisibility graph.
  // Recomputes this keyframe's edges from its map points' observations (edges
  // need >= 15 shared points; if none qualifies the best one is kept) and
  // updates the other side. The first call also sets the spanning-tree parent.
  void update_connections();
  void add_connection(KeyFrame* other, int weight);
  void erase_connection(KeyFrame* other);
  int weight(KeyFrame* other) const;
  // All neighbours by decreasing weight (ties by id).
  std::vector<KeyFrame*> covisibles() const;
  std::vector<KeyFrame*> best_covisibles(std::size_t n) const;
  std::vector<KeyFrame*> covisibles_with_weight(int min_weight) const;

  // Spanning tree.
  KeyFrame* parent() const { return parent_; }
  const std::set<KeyFrame*, KeyFrameIdLess>& children() const { return children_; }
  void add_child(KeyFrame* kf) { children_.insert(kf); }
  void erase_child(KeyFrame* kf) { children_.erase(kf); }
  void change_parent(KeyFrame* kf);

  // The map's origin keyframe (its first): anchors the gauge, never culled,
  // never gets a spanning-tree parent. Map::create_keyframe sets it; a merge
  // clears it on the absorbed map's origin. Defaults to id == 0.
  bool is_origin() const { return origin_; }
  void set_origin(bool origin) { origin_ = origin; }

  // A Gaussian prior on the camera centre that local BA adds for this
  // keyframe: residual sqrt_info * (centre - mean), world axes
  // (Motion.sparseViewKeyframePriorSigma: a keyframe made in a sparse view is
  // held near its centre at creation along its least certain directions).
  struct CentrePrior {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    Eigen::Matrix3d sqrt_info = Eigen::Matrix3d::Zero();
  };
  const std::optional<CentrePrior>& centre_prior() const { return centre_prior_; }
  void set_centre_prior(const CentrePrior& prior) { centre_prior_ = prior; }

  bool is_bad() const { return bad_; }
  // Culling: removes the keyframe from the covisibility graph and its points'
  // observations, re-parents its children. The origin keyframe can't be culled.
  void set_bad();
  // Set while local mapping uses the keyframe and it must not be culled.
  void set_not_erase(bool v) { not_erase_ = v; }

 private:
  void update_best_covisibles();

  std::uint64_t id_;
  std::uint64_t frame_id_;
  double timestamp_;
  std::shared_ptr<const CameraSetup> setup_;
  Eigen::Isometry3d T_cam_world_;
  Eigen::Isometry3d T_world_cam_;  // T_cam_world_.inverse(), set with it
  std::vector<cv::KeyPoint> keypoints_;
  cv::Mat descriptors_;
  std::vector<float> u_right_, depth_;
  std::shared_ptr<const FeatureGrid> grid_;
  std::vector<MapPointPtr> map_points_;

  std::map<KeyFrame*, int, KeyFrameIdLess> connections_;
  std::vector<KeyFrame*> ordered_connections_;
  std::vector<int> ordered_weights_;
  bool first_connection_ = true;
  KeyFrame* parent_ = nullptr;
  std::set<KeyFrame*, KeyFrameIdLess> children_;
  Eigen::Isometry3d T_cam_parent_ = Eigen::Isometry3d::Identity();  // set when culled
  bool bad_ = false;
  bool not_erase_ = false;
  bool origin_ = false;
  std::optional<CentrePrior> centre_prior_;
};

using KeyFramePtr = std::shared_ptr<KeyFrame>;

}  // namespace stillslam
