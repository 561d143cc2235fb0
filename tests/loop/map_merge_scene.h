#pragma once
// Two maps of one synthetic scene for map-merging tests (no images): points
// with random descriptors on a cylinder wall, keyframes on a circle looking
// outward, exact measurements. Each map is built as tracking would from its
// own first keyframe: map B's world frame is unknown to map A (an arbitrary
// rigid transform), points are re-observed by the next few keyframes of the
// same map only. Both maps share one set of id counters (as in an Atlas).
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "stillslam/map/frame.h"
#include "stillslam/map/map.h"
#include "stillslam/place/vocabulary.h"

namespace stillslam::test {

class MapMergeScene {
 public:
  explicit MapMergeScene(std::uint32_t seed = 7, int num_points = 3000) {
    CameraCalibration calib;
    calib.fx = 500;
    calib.fy = 500;
    calib.cx = 320;
    calib.cy = 240;
    calib.width = 640;
    calib.height = 480;
    setup_ = std::make_shared<CameraSetup>(PinholeCamera(calib, 40.0), ScalePyramid(OrbOptions{}), 40.0 / 500 * 40);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> angle(0, 2 * M_PI), height(-1.5, 1.5);
    std::uniform_int_distribution<int> byte(0, 255);
    for (int i = 0; i < num_points; ++i) {
      const double a = angle(rng);
      points_.emplace_back(5.0 * std::sin(a), height(rng), 5.0 * std::cos(a));
      std::array<std::uint8_t, 32> d{};
      for (auto& b : d) b = static_cast<std::uint8_t>(byte(rng));
      descriptors_.push_back(d);
    }
  }

  const std::shared_ptr<CameraSetup>& setup() const { return setup_; }
  const Eigen::Vector3d& point(std::size_t s) const { return points_[s]; }

  // The true camera pose at `deg` degrees on the circle (radius 1 m).
  static Eigen::Isometry3d true_T_world_cam(double deg) {
    const double a = deg * M_PI / 180.0;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(std::sin(a), 0, std::cos(a));
    return T;
  }

  // One map under construction: its frame is T_map_world * (true world).
  struct MapBuild {
    Map* map = nullptr;
    Eigen::Isometry3d T_map_world = Eigen::Isometry3d::Identity();
    int reuse_window = 6;
    int count = 0;
    std::map<std::size_t, std::pair<MapPointPtr, int>> live;  // scene point -> (map point, keyframe count)
    std::map<std::uint64_t, double> degrees;                  // keyframe id -> true angle
  };

  // Adds a keyframe at `deg` to the map (exact measurements, pose in the map's frame).
  KeyFramePtr add_keyframe(MapBuild& b, double deg) {
    const Eigen::Isometry3d T_cw_true = true_T_world_cam(deg).inverse();
    std::vector<cv::KeyPoint> kps;
    std::vector<float> u_right, depth;
    cv::Mat desc(0, 32, CV_8U);
    std::vector<std::pair<std::size_t, bool>> point_of_keypoint;
    for (std::size_t s = 0; s < points_.size(); ++s) {
      const Eigen::Vector3d p = T_cw_true * points_[s];
      const Eigen::Vector2d uv = setup_->camera.project(p);
      if (p.z() <= 0.3 || !setup_->camera.in_image(uv)) continue;
      const auto it = b.live.find(s);
      const bool reuse = it != b.live.end() && it->second.second + b.reuse_window >= b.count;
      kps.emplace_back(static_cast<float>(uv.x()), static_cast<float>(uv.y()), 31.f, 0.f, 1.f, 0);
      depth.push_back(static_cast<float>(p.z()));
      u_right.push_back(static_cast<float>(uv.x() - setup_->camera.bf() / p.z()));
      desc.push_back(cv::Mat(1, 32, CV_8U, descriptors_[s].data()).clone());
      point_of_keypoint.emplace_back(s, !reuse);
    }
    Frame frame(next_frame_id_, 0.1 * static_cast<double>(next_frame_id_), setup_, kps, kps, desc, u_right, depth);
    ++next_frame_id_;
    frame.set_pose((b.T_map_world * true_T_world_cam(deg)).inverse());
    KeyFramePtr kf = b.map->create_keyframe(frame);
    for (std::size_t k = 0; k < point_of_keypoint.size(); ++k) {
      const auto [s, fresh] = point_of_keypoint[k];
      if (fresh) b.live[s] = {b.map->create_map_point(b.T_map_world * points_[s], kf.get()), b.count};
      const MapPointPtr& mp = b.live[s].first;
      mp->add_observation(kf.get(), k);
      kf->set_map_point(k, mp);
    }
    for (const auto& mp : kf->map_points()) {
      if (!mp) continue;
      mp->compute_distinctive_descriptor();
      mp->update_normal_and_depth(setup_->pyramid);
    }
    kf->update_connections();
    b.degrees[kf->id()] = deg;
    ++b.count;
    return kf;
  }

  // A small vocabulary over the scene's descriptors (about one word per point).
  Vocabulary train_vocabulary() const {
    std::vector<cv::Mat> images;
    for (std::size_t start = 0; start < descriptors_.size(); start += 300) {
      cv::Mat d(0, 32, CV_8U);
      for (std::size_t s = start; s < std::min(descriptors_.size(), start + 300); ++s) {
        d.push_back(cv::Mat(1, 32, CV_8U, const_cast<std::uint8_t*>(descriptors_[s].data())).clone());
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
  std::shared_ptr<CameraSetup> setup_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<std::array<std::uint8_t, 32>> descriptors_;
  std::uint64_t next_frame_id_ = 0;
};

}  // namespace stillslam::test
