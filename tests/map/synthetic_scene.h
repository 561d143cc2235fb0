#pragma once
// A synthetic scene for map/tracking/mapping unit tests (no images): random
// 3D points with a fixed random descriptor each; frames are built by
// projecting the points with a known pose (keypoints at level 0, exact depth
// and virtual right coordinate), so matches can be checked by point identity.
#include <Eigen/Geometry>
#include <memory>
#include <random>
#include <vector>

#include "../common/synthetic_camera.h"
#include "stillslam/map/frame.h"

namespace stillslam::test {

class SyntheticScene {
 public:
  explicit SyntheticScene(int num_points = 1500, std::uint32_t seed = 7) : setup_(synthetic_camera_setup()) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> xy(-3.0, 3.0), z(2.0, 5.0);
    for (int i = 0; i < num_points; ++i) {
      points_.emplace_back(xy(rng), xy(rng), z(rng));
      descriptors_.push_back(random_descriptor(rng));
    }
  }

  const std::shared_ptr<CameraSetup>& setup() const { return setup_; }
  const std::vector<Eigen::Vector3d>& points() const { return points_; }
  // Moves one point (a dynamic object); it keeps its descriptor.
  void move_point(std::size_t i, const Eigen::Vector3d& offset) { points_[i] += offset; }

  // Frame seeing the scene from T_cam_world (pose NOT set on the frame).
  // point_of_keypoint receives the scene point index of every keypoint.
  Frame make_frame(std::uint64_t id, const Eigen::Isometry3d& T_cam_world,
                   std::vector<std::size_t>* point_of_keypoint = nullptr) const {
    std::vector<cv::KeyPoint> kps;
    std::vector<float> u_right, depth;
    std::vector<std::size_t> ids;
    cv::Mat desc(0, 32, CV_8U);
    for (std::size_t i = 0; i < points_.size(); ++i) {
      const Eigen::Vector3d p = T_cam_world * points_[i];
      if (p.z() <= 0.1) continue;
      const Eigen::Vector2d uv = setup_->camera.project(p);
      if (!setup_->camera.in_image(uv)) continue;
      cv::KeyPoint kp(static_cast<float>(uv.x()), static_cast<float>(uv.y()), 31.f, 0.f, 1.f, 0);
      kps.push_back(kp);
      depth.push_back(static_cast<float>(p.z()));
      u_right.push_back(static_cast<float>(uv.x() - setup_->camera.bf() / p.z()));
      desc.push_back(descriptor_row(descriptors_[i]));
      ids.push_back(i);
    }
    if (point_of_keypoint) *point_of_keypoint = ids;
    return Frame(id, 0.1 * static_cast<double>(id), setup_, kps, kps, desc, u_right, depth);
  }

 private:
  std::shared_ptr<CameraSetup> setup_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<SceneDescriptor> descriptors_;
};

inline Eigen::Isometry3d pose_at(double x, double y = 0, double yaw_deg = 0) {
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();
  T_world_cam.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  T_world_cam.translation() = Eigen::Vector3d(x, y, 0);
  return T_world_cam.inverse();  // T_cam_world
}

}  // namespace stillslam::test
