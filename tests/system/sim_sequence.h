#pragma once
// Renders a short synthetic sequence in memory (sim::Simulator) as
// SensorFrames plus ground truth, for end-to-end tests of the system.

#include "stillslam/io/dataset.h"
#include "stillslam/settings/settings.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/sim/sensor_frame.h"
#include "stillslam/sim/simulator.h"

namespace stillslam::test {

struct SimSequence {
  Settings settings;
  StereoCalibration stereo;
  std::vector<SensorFrame> frames;
  Trajectory groundtruth;
};

inline SimSequence render_sim_sequence(const std::string& trajectory, int frames, int width, int height,
                                       bool stereo) {
  sim::SimulationOptions opts;
  opts.trajectory = trajectory;
  opts.frames = frames;
  opts.width = width;
  opts.height = height;
  opts.no_people = true;
  opts.stereo = stereo;
  opts.supersampling = 1;
  opts.data_dir = std::filesystem::path(STILLSLAM_SOURCE_DIR) / "data";
  sim::Simulator simulator(opts);
  SimSequence seq;
  seq.settings.camera = simulator.camera();
  seq.settings.fps = 30;
  seq.settings.th_depth = 40;
  seq.settings.segmentation.enabled = false;
  seq.settings.orb.n_features = 1000;
  const double baseline = stereo ? opts.baseline : 40.0 / 535.4;
  seq.settings.bf = baseline * seq.settings.camera.fx;
  seq.stereo.left = simulator.camera();
  seq.stereo.right = simulator.camera();
  seq.stereo.baseline = opts.baseline;
  seq.stereo.rectified = true;
  for (int i = 0; i < simulator.frame_count(); ++i) {
    const sim::SimFrame f = simulator.render_frame(i);
    seq.frames.push_back(sim::to_sensor_frame(f, stereo ? SensorType::Stereo : SensorType::Rgbd));
    seq.groundtruth.push_back({f.timestamp, f.T_world_cam});
  }
  return seq;
}

}  // namespace stillslam::test
