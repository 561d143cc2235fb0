#pragma once
// A synthetic loop for loop-closing tests (no images): points with random
// descriptors on a cylinder wall around the origin, keyframes on a circle
// looking outward. The map is built as odometry would: keyframe i sits in a
// slowly drifting world W(angle) * truth, its new points are placed in that
// drifted world, and points are only re-observed by the next few keyframes,
// so when the circle comes back the old points are not re-associated (that
// is the loop closer's job). Keypoints and depths are exact projections of the
// true scene; the map (poses and points) drifts smoothly, so it is nearly
// consistent locally (a few pixels over the reuse window) and wrong globally.
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "stillslam/map/frame.h"
#include "stillslam/map/map.h"
#include "stillslam/place/vocabulary.h"

namespace stillslam::test {

class LoopScene {
 public:
  struct Options {
    int num_points = 3000;
    double wall_radius = 5.0;
    double camera_radius = 1.0;
    double step_deg = 10.0;
    int reuse_window = 6;          // a point is re-observed by this many later keyframes
    double drift_yaw_deg = 8.0;    // per full turn
    double drift_translation = 0.05;  // metres per full turn (sum of the per-step biases)
    std::uint32_t seed = 5;
  };

  explicit LoopScene(Options options) : options_(options) {
    CameraCalibration calib;
    calib.fx = 500;
    calib.fy = 500;
    calib.cx = 320;
    calib.cy = 240;
    calib.width = 640;
    calib.height = 480;
    setup_ = std::make_shared<CameraSetup>(PinholeCamera(calib, 40.0), ScalePyramid(OrbOptions{}), 40.0 / 500 * 40);
    std::mt19937 rng(options.seed);
    std::uniform_real_distribution<double> angle(0, 2 * M_PI), height(-1.5, 1.5);
    std::uniform_int_distribution<int> byte(0, 255);
    for (int i = 0; i < options.num_points; ++i) {
      const double a = angle(rng);
      points_.emplace_back(options.wall_radius * std::sin(a), height(rng), options.wall_radius * std::cos(a));
      std::array<std::uint8_t, 32> d{};
      for (auto& b : d) b = static_cast<std::uint8_t>(byte(rng));
      descriptors_.push_back(d);
    }
  }
  LoopScene() : LoopScene(Options{}) {}

  const std::shared_ptr<CameraSetup>& setup() const { return setup_; }
  double angle_of(int i) const { return options_.step_deg * i * M_PI / 180.0; }

  Eigen::Isometry3d true_T_world_cam(int i) const {
    const double a = angle_of(i);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix();
    T.translation() = options_.camera_radius * Eigen::Vector3d(std::sin(a), 0, std::cos(a));
    return T;
  }
  // The drift of the world at keyframe i (identity at i = 0): odometry with a
  // constant bias E per step (in the camera frame, as visual odometry drifts),
  // T_world_cam_drifted(i) = T_world_cam_drifted(i - 1) * T_true(i-1, i) * E.
  Eigen::Isometry3d drift(int i) const {
    const double steps_per_turn = 360.0 / options_.step_deg;
    Eigen::Isometry3d E = Eigen::Isometry3d::Identity();
    E.linear() = Eigen::AngleAxisd(options_.drift_yaw_deg / steps_per_turn * M_PI / 180.0, Eigen::Vector3d::UnitY())
                     .toRotationMatrix();
    E.translation() = options_.drift_translation / steps_per_turn * Eigen::Vector3d(1.0, 0.1, 0.5).normalized();
    Eigen::Isometry3d T_drifted = true_T_world_cam(0);
    for (int k = 1; k <= i; ++k) {
      T_drifted = T_drifted * (true_T_world_cam(k - 1).inverse() * true_T_world_cam(k)) * E;
    }
    return T_drifted * true_T_world_cam(i).inverse();
  }

  // A frame with exact measurements from a true pose (no pose set): for
  // relocalization queries.
  Frame make_frame(std::uint64_t id, const Eigen::Isometry3d& T_world_cam_true) const {
    const Eigen::Isometry3d T_cw = T_world_cam_true.inverse();
    std::vector<cv::KeyPoint> kps;
    std::vector<float> u_right, depth;
    cv::Mat desc(0, 32, CV_8U);
    for (std::size_t s = 0; s < points_.size(); ++s) {
      const Eigen::Vector3d p = T_cw * points_[s];
      const Eigen::Vector2d uv = setup_->camera.project(p);
      if (p.z() <= 0.3 || !setup_->camera.in_image(uv)) continue;
      kps.emplace_back(static_cast<float>(uv.x()), static_cast<float>(uv.y()), 31.f, 0.f, 1.f, 0);
      depth.push_back(static_cast<float>(p.z()));
      u_right.push_back(static_cast<float>(uv.x() - setup_->camera.bf() / p.z()));
      desc.push_back(cv::Mat(1, 32, CV_8U, const_cast<std::uint8_t*>(descriptors_[s].data())).clone());
    }
    return Frame(id, 0.1 * static_cast<double>(id), setup_, kps, kps, desc, u_right, depth);
  }

  // Adds keyframe i (call with i = 0, 1, 2, ... in order).
  KeyFramePtr add_keyframe(int i) {
    const Eigen::Isometry3d T_cw_true = true_T_world_cam(i).inverse();
    const Eigen::Isometry3d T_wc_drift = drift(i) * true_T_world_cam(i);
    std::vector<cv::KeyPoint> kps;
    std::vector<float> u_right, depth;
    std::vector<MapPointPtr> slots;
    cv::Mat desc(0, 32, CV_8U);
    std::vector<std::pair<std::size_t, bool>> point_of_keypoint;  // scene index, new?
    for (std::size_t s = 0; s < points_.size(); ++s) {
      const Eigen::Vector3d p = T_cw_true * points_[s];  // measurements are exact
      const Eigen::Vector2d uv = setup_->camera.project(p);
      if (p.z() <= 0.3 || !setup_->camera.in_image(uv)) continue;
      const auto it = live_.find(s);
      const bool reuse = it != live_.end() && it->second.second + options_.reuse_window >= i;
      kps.emplace_back(static_cast<float>(uv.x()), static_cast<float>(uv.y()), 31.f, 0.f, 1.f, 0);
      depth.push_back(static_cast<float>(p.z()));
      u_right.push_back(static_cast<float>(uv.x() - setup_->camera.bf() / p.z()));
      desc.push_back(cv::Mat(1, 32, CV_8U, descriptors_[s].data()).clone());
      point_of_keypoint.emplace_back(s, !reuse);
    }
    Frame frame(static_cast<std::uint64_t>(i), 0.1 * i, setup_, kps, kps, desc, u_right, depth);
    frame.set_pose(T_wc_drift.inverse());
    KeyFramePtr kf = map_.create_keyframe(frame);
    for (std::size_t k = 0; k < point_of_keypoint.size(); ++k) {
      const auto [s, fresh] = point_of_keypoint[k];
      if (fresh) {
        live_[s] = {map_.create_map_point(drift(i) * points_[s], kf.get()), i};
      }
      const MapPointPtr& mp = live_[s].first;
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

  Map& map() { return map_; }

  // A small vocabulary over the scene's descriptors.
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
    o.levels = 4;  // about one word per scene point: unrelated views share few words
    o.seed = 1;
    return Vocabulary::train(images, o);
  }

  // Largest camera-centre error of the map's keyframes against the truth.
  double max_position_error() const {
    double e = 0;
    for (const auto& kf : map_.keyframes()) {
      const int i = static_cast<int>(kf->id());
      e = std::max(e, (kf->camera_center() - true_T_world_cam(i).translation()).norm());
    }
    return e;
  }
  double max_rotation_error_deg() const {
    double e = 0;
    for (const auto& kf : map_.keyframes()) {
      const int i = static_cast<int>(kf->id());
      const Eigen::Matrix3d dR = kf->T_world_cam().linear().transpose() * true_T_world_cam(i).linear();
      e = std::max(e, Eigen::AngleAxisd(dR).angle() * 180.0 / M_PI);
    }
    return e;
  }

 private:
  Options options_;
  std::shared_ptr<CameraSetup> setup_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<std::array<std::uint8_t, 32>> descriptors_;
  Map map_;
  std::map<std::size_t, std::pair<MapPointPtr, int>> live_;  // scene point -> (map point, creating keyframe)
};

}  // namespace stillslam::test
