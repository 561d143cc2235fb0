#pragma once
// In-process simulator: builds the room, the camera path and the moving people
// from SimulationOptions and renders any frame on demand. Use it directly in
// tests that want images in memory; write_sequence() (sequence_writer.h) puts
// a whole sequence on disk in TUM RGB-D (and EuRoC stereo) layout.
//
//   sim::SimulationOptions opts;
//   opts.trajectory = "halfsphere"; opts.frames = 60; opts.width = 320; opts.height = 240;
//   sim::Simulator simulator(opts);
//   sim::SimFrame f = simulator.render_frame(0);   // f.bgr, f.depth, f.mask, f.T_world_cam
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "stillslam/geometry/camera_calibration.h"
#include "stillslam/sim/camera_motion.h"
#include "stillslam/sim/dynamic_objects.h"
#include "stillslam/sim/noise.h"
#include "stillslam/sim/quad.h"
#include "stillslam/sim/renderer.h"
#include "stillslam/sim/simulation_options.h"

namespace stillslam::sim {

struct SimFrame {
  int index = 0;
  std::int64_t stamp_ns = 0;  // microsecond-rounded
  double timestamp = 0;       // seconds
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();  // mid-exposure pose
  cv::Mat bgr;         // CV_8UC3
  cv::Mat depth;       // CV_32FC1 metres, 0 = no data (noisy when options.noise > 0)
  cv::Mat mask;        // CV_8UC1: 255 on moving people/objects (ground truth), else 0
  cv::Mat dynamic_ids; // CV_16UC1: which moving thing (0 = static)
  cv::Mat right_bgr;   // CV_8UC3, stereo only: right camera of the rectified pair
  cv::Mat right_gray;  // CV_8UC1, the same in gray
};

class Simulator {
 public:
  explicit Simulator(SimulationOptions options);

  int frame_count() const { return frames_; }
  SimFrame render_frame(int index) const;

  const SimulationOptions& options() const { return options_; }
  const CameraCalibration& camera() const { return renderer_->camera(); }
  const Renderer& renderer() const { return *renderer_; }
  const CameraMotion& motion() const { return motion_; }
  Eigen::Isometry3d T_world_scene() const { return T_world_scene_; }
  // Right camera of the stereo rig in the left camera frame (x = baseline).
  Eigen::Isometry3d T_left_right() const;
  std::int64_t stamp_ns(int index) const;
  Eigen::Isometry3d pose(int index) const;
  // Static room plus the moving things at time t (seconds since the start)
  // seen from T_world_cam (billboards face it, the occluder stands in front of it).
  std::vector<Quad> quads_at(double t, const Eigen::Isometry3d& T_world_cam) const;
  const std::vector<Quad>& static_quads() const { return static_quads_; }
  const DynamicObjects& dynamic_objects() const { return *dynamic_; }

 private:
  SimulationOptions options_;
  NoiseModel noise_;
  CameraMotion motion_;
  Eigen::Isometry3d T_world_scene_ = Eigen::Isometry3d::Identity();
  std::unique_ptr<Renderer> renderer_;
  std::vector<Quad> static_quads_;
  std::unique_ptr<DynamicObjects> dynamic_;
  int frames_ = 0;
};

}  // namespace stillslam::sim
