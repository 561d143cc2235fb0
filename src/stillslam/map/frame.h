#pragma once
// One camera frame as seen by tracking: undistorted keypoints (the dynamic
// ones already removed by the frame builder), descriptors, per keypoint the
// right/virtual-right coordinate and depth, the matched map point and an
// outlier flag, plus the estimated pose.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "stillslam/features/feature_grid.h"
#include "stillslam/map/camera_setup.h"
#include "stillslam/map/map_point.h"

namespace stillslam {

class KeyFrame;

// A dynamic instance carried to a frame from an older segmentation (async
// mode): its mask (image size, 255 inside, without margin) and its median
// depth in this frame (metres; 0: unknown).
struct CarriedInstance {
  cv::Mat1b mask;
  float depth = 0;
};

class Frame {
 public:
  Frame() = default;
  // keypoints_raw: detected (possibly distorted) positions; keypoints:
  // undistorted; u_right / depth < 0 where unknown. All of one size.
  Frame(std::uint64_t id, double timestamp, std::shared_ptr<const CameraSetup> setup,
        std::vector<cv::KeyPoint> keypoints_raw, std::vector<cv::KeyPoint> keypoints,
        cv::Mat descriptors, std::vector<float> u_right, std::vector<float> depth);

  std::uint64_t id() const { return id_; }
  double timestamp() const { return timestamp_; }
  const CameraSetup& setup() const { return *setup_; }
  const std::shared_ptr<const CameraSetup>& setup_ptr() const { return setup_; }

  std::size_t size() const { return keypoints_.size(); }
  const std::vector<cv::KeyPoint>& keypoints() const { return keypoints_; }
  const std::vector<cv::KeyPoint>& keypoints_raw() const { return keypoints_raw_; }
  const cv::KeyPoint& keypoint(std::size_t i) const { return keypoints_[i]; }
  const cv::Mat& descriptors() const { return descriptors_; }
  const std::uint8_t* descriptor(std::size_t i) const { return descriptors_.ptr<std::uint8_t>(static_cast<int>(i)); }
  const std::vector<float>& u_right() const { return u_right_; }
  const std::vector<float>& depth() const { return depth_; }
  float u_right(std::size_t i) const { return u_right_[i]; }
  float depth(std::size_t i) const { return depth_[i]; }
  const std::shared_ptr<const FeatureGrid>& grid() const { return grid_; }
  std::vector<std::size_t> features_in_area(float x, float y, float r, int min_level = -1,
                                            int max_level = -1) const {
    return grid_->features_in_area(x, y, r, min_level, max_level);
  }
  int num_with_depth() const;
  // The dynamic mask (255: hidden, image size) and the share of the image
  // it covers; empty and 0 without segmentation.
  const cv::Mat1b& dynamic_mask() const { return dynamic_mask_; }
  float masked_fraction() const { return masked_fraction_; }
  void set_dynamic_mask(cv::Mat1b mask);
  // Processed frames between the segmented frame the mask comes from and this
  // one (0: this frame's own segmentation; -1: no segmentation).
  int mask_age() const { return mask_age_; }
  void set_mask_age(int age) { mask_age_ = age; }
  // With a carried mask (age > 0, mask propagation): the instances it was made
  // of; empty otherwise.
  const std::vector<CarriedInstance>& carried_instances() const { return carried_instances_; }
  void set_carried_instances(std::vector<CarriedInstance> instances) { carried_instances_ = std::move(instances); }

  // Matched map points and outlier flags.
  const MapPointPtr& map_point(std::size_t i) const { return map_points_[i]; }
  const std::vector<MapPointPtr>& map_points() const { return map_points_; }
  void set_map_point(std::size_t i, MapPointPtr mp) { map_points_[i] = std::move(mp); }
  void clear_map_points();
  bool is_outlier(std::size_t i) const { return outlier_[i] != 0; }
  void set_outlier(std::size_t i, bool v) { outlier_[i] = v ? 1 : 0; }
  int num_matches() const;

  // Pose.
  bool has_pose() const { return T_cam_world_.has_value(); }
  const Eigen::Isometry3d& T_cam_world() const { return *T_cam_world_; }
  Eigen::Vector3d camera_center() const { return T_cam_world_->inverse().translation(); }
  void set_pose(const Eigen::Isometry3d& T_cam_world) { T_cam_world_ = T_cam_world; }
  // World point of a keypoint with depth (needs the pose).
  std::optional<Eigen::Vector3d> unproject(std::size_t i) const;

  const std::shared_ptr<KeyFrame>& reference_keyframe() const { return reference_keyframe_; }
  void set_reference_keyframe(std::shared_ptr<KeyFrame> kf) { reference_keyframe_ = std::move(kf); }

 private:
  std::uint64_t id_ = 0;
  double timestamp_ = 0;
  std::shared_ptr<const CameraSetup> setup_;
  std::vector<cv::KeyPoint> keypoints_raw_, keypoints_;
  cv::Mat descriptors_;
  std::vector<float> u_right_, depth_;
  std::shared_ptr<const FeatureGrid> grid_;
  std::vector<MapPointPtr> map_points_;
  std::vector<char> outlier_;
  std::optional<Eigen::Isometry3d> T_cam_world_;
  std::shared_ptr<KeyFrame> reference_keyframe_;
  cv::Mat1b dynamic_mask_;
  float masked_fraction_ = 0;
  int mask_age_ = -1;
  std::vector<CarriedInstance> carried_instances_;
};

}  // namespace stillslam
