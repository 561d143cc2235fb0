#pragma once
// The world of the loop and map-merging test scenes (no images): points with
// random descriptors on a cylinder wall around the origin, seen by a pinhole
// camera with exact measurements, and the odometry-like way those scenes
// build keyframes: a scene point is re-associated only by keyframes within
// a reuse window of the one that created it.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "../common/synthetic_camera.h"  // relative: benches include this header too
#include "stillslam/map/frame.h"
#include "stillslam/map/map.h"
#include "stillslam/place/vocabulary.h"

namespace stillslam::test {

class CylinderWorld {
 public:
  // Scene point -> (its map point, the keyframe count that created it).
  using LivePoints = std::map<std::size_t, std::pair<MapPointPtr, int>>;

  CylinderWorld(int num_points, double wall_radius, std::uint32_t seed) : setup_(synthetic_camera_setup()) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> angle(0, 2 * M_PI), height(-1.5, 1.5);
    for (int i = 0; i < num_points; ++i) {
      const double a = angle(rng);
      points_.emplace_back(wall_radius * std::sin(a), height(rng), wall_radius * std::cos(a));
      descriptors_.push_back(random_descriptor(rng));
    }
  }

  const std::shared_ptr<CameraSetup>& setup() const { return setup_; }
  const Eigen::Vector3d& point(std::size_t s) const { return points_[s]; }

  // A frame with exact measurements from a true pose (no pose set).
  Frame make_frame(std::uint64_t id, const Eigen::Isometry3d& T_world_cam_true) const {
    return observe(id, T_world_cam_true).frame;
  }

  // Adds a keyframe seen from a true pose to `map`, whose frame is
  // T_map_world * (true world): new points are placed there, points created
  // by keyframe counts within reuse_window of `count` are re-associated.
  KeyFramePtr add_keyframe(Map& map, std::uint64_t frame_id, const Eigen::Isometry3d& T_world_cam_true,
                           const Eigen::Isometry3d& T_map_world, LivePoints& live, int count,
                           int reuse_window) const {
    Observation o = observe(frame_id, T_world_cam_true);
    o.frame.set_pose((T_map_world * T_world_cam_true).inverse());
    KeyFramePtr kf = map.create_keyframe(o.frame);
    for (std::size_t k = 0; k < o.scene_points.size(); ++k) {
      const std::size_t s = o.scene_points[k];
      const auto it = live.find(s);
      if (it == live.end() || it->second.second + reuse_window < count) {
        live[s] = {map.create_map_point(T_map_world * points_[s], kf.get()), count};
      }
      const MapPointPtr& mp = live[s].first;
      mp->add_observation(kf.get(), k);
      kf->set_map_point(k, mp);
    }
    for (const auto& mp : kf->map_points()) {
      if (!mp) continue;
      mp->compute_distinctive_descriptor();
      mp->update_normal_and_depth(setup_->pyramid);
    }
    kf->update_connections();
    return kf;
  }

  // A small vocabulary over the scene's descriptors: about one word per
  // scene point, so unrelated views share few words.
  Vocabulary train_vocabulary() const {
    std::vector<cv::Mat> images;
    for (std::size_t start = 0; start < descriptors_.size(); start += 300) {
      cv::Mat d(0, 32, CV_8U);
      for (std::size_t s = start; s < std::min(descriptors_.size(), start + 300); ++s) {
        d.push_back(descriptor_row(descriptors_[s]));
      }
      images.push_back(d);
    }
    VocabularyOptions o;
    o.branching = 8;
    o.levels = 4;
    o.seed = 1;
    return Vocabulary::train(images, o);
  }

 private:
  struct Observation {
    Frame frame;
    std::vector<std::size_t> scene_points;  // per keypoint
  };

  // Every scene point in front of the camera and inside the image, in scene order.
  Observation observe(std::uint64_t id, const Eigen::Isometry3d& T_world_cam_true) const {
    const Eigen::Isometry3d T_cw = T_world_cam_true.inverse();
    std::vector<cv::KeyPoint> kps;
    std::vector<float> u_right, depth;
    std::vector<std::size_t> scene_points;
    cv::Mat desc(0, 32, CV_8U);
    for (std::size_t s = 0; s < points_.size(); ++s) {
      const Eigen::Vector3d p = T_cw * points_[s];
      const Eigen::Vector2d uv = setup_->camera.project(p);
      if (p.z() <= 0.3 || !setup_->camera.in_image(uv)) continue;
      kps.emplace_back(static_cast<float>(uv.x()), static_cast<float>(uv.y()), 31.f, 0.f, 1.f, 0);
      depth.push_back(static_cast<float>(p.z()));
      u_right.push_back(static_cast<float>(uv.x() - setup_->camera.bf() / p.z()));
      desc.push_back(descriptor_row(descriptors_[s]));
      scene_points.push_back(s);
    }
    return {Frame(id, 0.1 * static_cast<double>(id), setup_, kps, kps, desc, u_right, depth), std::move(scene_points)};
  }

  std::shared_ptr<CameraSetup> setup_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<SceneDescriptor> descriptors_;
};

}  // namespace stillslam::test
