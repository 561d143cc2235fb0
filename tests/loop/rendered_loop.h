#pragma once
// The loop-closing bar on a rendered sequence, shared by the end-to-end test
// and bench/bench_loop_closing.cpp: the simulator's "loop" path (one turn
// around the room in CameraMotion::kLoopPeriod seconds, then on past the
// start) rendered in memory with sensor noise, run through the whole System
// with loop closing on or off, and scored against the ground truth.

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <thread>
#include <vector>

#include "stillslam/core/stopwatch.h"
#include "stillslam/eval/evaluate.h"
#include "stillslam/io/dataset.h"
#include "stillslam/settings/settings.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/sim/sensor_frame.h"
#include "stillslam/sim/simulator.h"
#include "stillslam/system/system.h"

namespace stillslam::test {

struct RenderedLoopOptions {
  // 10 Hz keeps the test short: 1.8 deg and 1.6 cm of camera motion per frame.
  double fps = 10;
  // One turn (200 frames at 10 Hz) plus 3 s past the start.
  int frames = 230;
  int width = 320, height = 240;
  int noise = 1;  // sim noise level: image noise, depth noise sigma = k z^2, motion blur
  std::uint64_t seed = 0;
  int features = 1000;  // ORBextractor.nFeatures (as in the settings `stillslam simulate` writes)
};

struct RenderedLoop {
  Settings settings;
  std::vector<SensorFrame> frames;
  Trajectory groundtruth;
};

inline std::filesystem::path repository_data_dir() { return std::filesystem::path(STILLSLAM_SOURCE_DIR) / "data"; }

inline std::filesystem::path committed_vocabulary() {
  return std::filesystem::path(STILLSLAM_SOURCE_DIR) / "vocab" / "orb_vocabulary.bin";
}

// RGB-D settings as `stillslam simulate` writes them (Kinect-like bf = 40 px
// at fx 535.4, ThDepth 40), scaled to the image size.
inline Settings rendered_loop_settings(const CameraCalibration& camera, double fps, int features) {
  Settings s;
  s.camera = camera;
  s.fps = fps;
  s.tracking.max_frames_between_keyframes = static_cast<int>(fps);  // as load_settings does
  s.th_depth = 40;
  s.bf = 40.0 / 535.4 * camera.fx;
  s.segmentation.enabled = false;
  s.orb.n_features = features;
  return s;
}

inline RenderedLoop render_loop(const RenderedLoopOptions& o) {
  sim::SimulationOptions opts;
  opts.trajectory = "loop";
  opts.frames = o.frames;
  opts.fps = o.fps;
  opts.width = o.width;
  opts.height = o.height;
  opts.no_people = true;
  opts.noise = o.noise;
  opts.seed = o.seed;
  opts.supersampling = 1;
  opts.data_dir = repository_data_dir();
  const sim::Simulator simulator(opts);
  RenderedLoop out;
  out.settings = rendered_loop_settings(simulator.camera(), o.fps, o.features);
  out.frames.resize(static_cast<std::size_t>(simulator.frame_count()));
  out.groundtruth.resize(out.frames.size());
  // Frames are independent (one RNG stream each): render on both cores.
  auto render = [&](std::size_t begin, std::size_t step) {
    for (std::size_t i = begin; i < out.frames.size(); i += step) {
      const sim::SimFrame f = simulator.render_frame(static_cast<int>(i));
      out.frames[i] = sim::to_sensor_frame(f);
      out.groundtruth[i] = {f.timestamp, f.T_world_cam};
    }
  };
  std::thread other(render, 1, 2);
  render(0, 2);
  other.join();
  return out;
}

struct LoopRunOptions {
  bool loop_closing = true;
  bool deterministic = true;
  bool global_bundle_adjustment = true;  // false: the essential graph alone corrects the loop
  std::filesystem::path vocabulary = committed_vocabulary();
};

struct LoopRun {
  std::vector<FrameStats> frames;
  Trajectory trajectory;
  LoopCloserStats loop_closer;
  // Index of the frame after whose processing each loop was seen closed
  // (deterministic: the frame whose keyframe closed it).
  std::vector<std::size_t> closed_at;
  double seconds = 0;
};

inline LoopRun run_loop(const Settings& settings, const std::vector<SensorFrame>& frames, const LoopRunOptions& o) {
  SystemOptions options;
  options.deterministic = o.deterministic;
  options.vocabulary_path = o.vocabulary;
  options.loop_closing = o.loop_closing;
  options.use_segmentation = false;
  Settings tuned = settings;
  tuned.loop_closing.run_global_bundle_adjustment = o.global_bundle_adjustment;
  // ORB-SLAM's 500 keypoints with depth to start are meant for 1000 features.
  tuned.tracking.init_min_keypoints = std::min(500, settings.orb.n_features / 2);
  LoopRun out;
  Stopwatch time;
  System system(tuned, SensorType::Rgbd, std::nullopt, options);
  int closed = 0;
  for (const SensorFrame& f : frames) {
    FrameStats stats = system.process(f);
    mark_start_frames_posed(out.frames, stats);  // the frames the map's start waited on
    out.frames.push_back(std::move(stats));
    const int now = system.loop_closer_stats().loops_closed;
    for (; closed < now; ++closed) out.closed_at.push_back(out.frames.size() - 1);
  }
  system.shutdown();
  out.loop_closer = system.loop_closer_stats();
  for (; closed < out.loop_closer.loops_closed; ++closed) out.closed_at.push_back(frames.size() - 1);
  out.trajectory = system.trajectory();
  out.seconds = time.elapsed_ms() / 1000.0;
  return out;
}

// Translation error (m) of the estimate at ground-truth frame `index`, both
// expressed relative to the first frame (the system's world frame): what
// odometry drift looks like, no alignment.
inline std::optional<double> error_at(const Trajectory& groundtruth, const Trajectory& estimate, std::size_t index) {
  if (index >= groundtruth.size()) return std::nullopt;
  const double t = groundtruth[index].timestamp;
  const auto it = std::find_if(estimate.begin(), estimate.end(),
                               [&](const StampedPose& p) { return std::abs(p.timestamp - t) < 1e-6; });
  if (it == estimate.end()) return std::nullopt;
  const Eigen::Isometry3d T_gt = groundtruth.front().T_world_cam.inverse() * groundtruth[index].T_world_cam;
  return (T_gt.translation() - it->T_world_cam.translation()).norm();
}

inline double ate_rmse(const Trajectory& groundtruth, const Trajectory& estimate) {
  return evaluate(groundtruth, estimate, EvaluationOptions{}).ape_stats.rmse;
}

}  // namespace stillslam::test
