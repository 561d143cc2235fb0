#pragma once
// Writes a simulated sequence to disk.
//
// TUM RGB-D layout (always):
//   rgb/<t>.png (8-bit BGR), depth/<t>.png (16-bit, 5000 per metre, 0 = no data),
//   masks/<t>.png (ground truth: 255 on moving people/objects, 0 static),
//   instances/<t>.png (16-bit: the dynamic id of each pixel, 0 static) and
//   instances.txt (per id: kind, class, whether it moves),
//   rgb.txt, depth.txt, associations.txt (`t rgb/<t>.png t depth/<t>.png`),
//   groundtruth.txt (TUM, T_world_cam of the colour/left camera),
//   settings.yaml (stillslam / ORB-SLAM3 keys, Segmentation.model absolute).
// EuRoC stereo layout (options.stereo):
//   mav0/cam{0,1}/data.csv + data/<ns>.png (8-bit grey, already rectified),
//   mav0/cam{0,1}/sensor.yaml (zero distortion, T_BS: body = cam0),
//   mav0/state_groundtruth_estimate0/data.csv, settings_stereo.yaml.
//
//   sim::SimulationOptions opts;
//   opts.frames = 60;
//   sim::write_sequence(dir, opts);   // then open_dataset(dir, ...) / stillslam run --input dir
#include <filesystem>
#include <functional>

#include "stillslam/sim/simulation_options.h"

namespace stillslam::sim {

struct SequenceSummary {
  int frames = 0;
  double seconds = 0;          // wall time of the whole write
  double render_ms_mean = 0;   // per frame (colour + depth + mask [+ right])
  std::filesystem::path settings, settings_stereo;
};

// progress(done, total) is called after each frame (may be empty).
SequenceSummary write_sequence(const std::filesystem::path& dir, const SimulationOptions& options,
                               const std::function<void(int, int)>& progress = {});

}  // namespace stillslam::sim
