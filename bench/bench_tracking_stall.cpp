// How long the tracker's frames take while a loop is detected, corrected and
// globally adjusted (issue #14: the tracker's longest frame during a loop
// closure should be at most 2x its median). Runs the System in threaded mode
// (as `stillslam run`) over a sequence with a loop, e.g.
//
//   stillslam simulate --out /tmp/loop --trajectory loop --frames 700 --no-people --noise 1
//   build/bench/bench_tracking_stall --sequence /tmp/loop [--runs 3] [--max-frames N]
//
// Per run it prints the tracker's time per frame (wall and thread CPU: the
// wall time includes waiting for the map lock and for a core) over all frames,
// and its maximum over the loop window: from the frame after which loop
// closing had a new loop until the last frame during which its global BA ran.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "stillslam/core/error.h"
#include "stillslam/io/dataset.h"
#include "stillslam/settings/settings.h"
#include "stillslam/system/system.h"

using namespace stillslam;

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("tracker frame times around loop closures (threaded mode)");
  std::string sequence, config, vocabulary = std::string(STILLSLAM_SOURCE_DIR) + "/vocab/orb_vocabulary.bin";
  int runs = 3;
  std::size_t max_frames = 0;
  app.add_option("--sequence", sequence, "dataset folder with a loop")->required();
  app.add_option("--config", config, "settings (default: settings.yaml in the folder)");
  app.add_option("--vocabulary", vocabulary, "ORB vocabulary")->capture_default_str();
  app.add_option("--runs", runs, "runs")->capture_default_str();
  app.add_option("--max-frames", max_frames, "at most N frames");
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::warn);
  try {
    const Settings settings = load_settings(config.empty() ? sequence + "/settings.yaml" : config);
    const auto dataset = open_dataset(sequence, settings);
    std::size_t n = dataset->size();
    if (max_frames > 0) n = std::min(n, max_frames);
    std::vector<SensorFrame> frames;
    for (std::size_t i = 0; i < n; ++i) frames.push_back(dataset->load(i));
    std::printf("%-4s %7s %7s %7s %7s | %5s %7s %7s %6s | %7s %7s\n", "run", "median", "p95", "max", "max/med",
                "loops", "window", "win.max", "w/med", "cpu.med", "cpu.max");
    for (int run = 1; run <= runs; ++run) {
      SystemOptions options;
      options.use_segmentation = false;
      options.vocabulary_path = vocabulary;
      System system(settings, dataset->sensor(), dataset->rectified_stereo(), options);
      std::vector<double> wall, cpu;
      std::vector<int> loops;
      std::vector<bool> gba;
      for (const SensorFrame& f : frames) {
        const FrameStats s = system.process(f);
        wall.push_back(s.tracking_ms);
        cpu.push_back(s.tracking_cpu_ms);
        loops.push_back(s.loops_closed);
        gba.push_back(s.global_bundle_adjustment_running);
      }
      system.shutdown();
      // Loop window: from the first frame that saw a new loop to the last
      // frame during which a global BA ran (or the loop frame itself).
      std::size_t begin = wall.size(), end = 0;
      for (std::size_t i = 0; i < wall.size(); ++i) {
        const bool new_loop = loops[i] > (i > 0 ? loops[i - 1] : 0);
        if (new_loop) {
          begin = std::min(begin, i > 0 ? i - 1 : 0);
          end = std::max(end, i);
        }
        if (gba[i] && begin < wall.size()) end = std::max(end, i);
      }
      double window_max = 0;
      for (std::size_t i = begin; i <= end && i < wall.size(); ++i) window_max = std::max(window_max, wall[i]);
      const double med = median(wall);
      std::printf("%-4d %7.2f %7.2f %7.2f %7.2f | %5d %3zu-%-3zu %7.2f %6.2f | %7.2f %7.2f\n", run, med,
                  percentile(wall, 0.95), *std::max_element(wall.begin(), wall.end()),
                  *std::max_element(wall.begin(), wall.end()) / med, loops.back(), begin < wall.size() ? begin : 0,
                  end, window_max, window_max / med, median(cpu), *std::max_element(cpu.begin(), cpu.end()));
    }
    std::printf("times: tracker ms per frame (wall unless cpu.*); window: frames from the loop detection to the "
                "end of the global BA; w/med: window max / median (bar: <= 2)\n");
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_tracking_stall: %s\n", e.what());
    return 1;
  }
  return 0;
}
