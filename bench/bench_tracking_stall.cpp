// How long the tracker's frames take while a loop is detected, corrected and
// globally adjusted (issue #14: the tracker's longest frame during a loop
// closure should be at most 2x its median). Runs the System in threaded mode
// (as `stillslam run`) over a sequence with a loop, e.g.
//
//   stillslam simulate --out /tmp/loop --trajectory loop --frames 700 --no-people --noise 1
//   build/bench/bench_tracking_stall --sequence /tmp/loop [--runs 3] [--max-frames N] [--paced]
//
// Per run it prints, for the whole frame (frame building + tracking) and for
// the tracker alone, the median time per frame and the maximum over the loop
// window: from the frame before loop closing had a new loop until the last
// frame during which its global BA ran. Times are wall clock: they include
// waiting for the map lock and for a core. --paced feeds frames at the
// camera's rate (Camera.fps) as a live camera would, instead of back to back.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>
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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("tracker frame times around loop closures (threaded mode)");
  std::string sequence, config, vocabulary = std::string(STILLSLAM_SOURCE_DIR) + "/vocab/orb_vocabulary.bin";
  int runs = 3;
  std::size_t max_frames = 0;
  bool paced = false;
  app.add_option("--sequence", sequence, "dataset folder with a loop")->required();
  app.add_option("--config", config, "settings (default: settings.yaml in the folder)");
  app.add_option("--vocabulary", vocabulary, "ORB vocabulary")->capture_default_str();
  app.add_option("--runs", runs, "runs")->capture_default_str();
  app.add_option("--max-frames", max_frames, "at most N frames");
  app.add_flag("--paced", paced, "feed frames at Camera.fps instead of back to back");
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::warn);
  try {
    const Settings settings = load_settings(config.empty() ? sequence + "/settings.yaml" : config);
    const auto dataset = open_dataset(sequence, settings);
    std::size_t n = dataset->size();
    if (max_frames > 0) n = std::min(n, max_frames);
    std::vector<SensorFrame> frames;
    for (std::size_t i = 0; i < n; ++i) frames.push_back(dataset->load(i));
    std::printf("%-4s %5s %9s | %8s %8s %8s %6s | %8s %8s %8s %6s\n", "run", "loops", "window", "frame.med",
                "frame.max", "win.max", "w/med", "track.med", "track.max", "win.max", "w/med");
    for (int run = 1; run <= runs; ++run) {
      SystemOptions options;
      options.use_segmentation = false;
      options.vocabulary_path = vocabulary;
      System system(settings, dataset->sensor(), dataset->rectified_stereo(), options);
      std::vector<double> total, wall;
      std::vector<int> loops;
      std::vector<bool> gba;
      const auto start = std::chrono::steady_clock::now();
      for (const SensorFrame& f : frames) {
        if (paced) {
          const double due = (f.timestamp - frames.front().timestamp);
          std::this_thread::sleep_until(start + std::chrono::duration<double>(due));
        }
        const FrameStats s = system.process(f);
        total.push_back(s.total_ms);
        wall.push_back(s.tracking_ms);
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
      auto window_max = [&](const std::vector<double>& t) {
        double m = 0;
        for (std::size_t i = begin; i <= end && i < t.size(); ++i) m = std::max(m, t[i]);
        return m;
      };
      const double total_med = median(total), track_med = median(wall);
      std::printf("%-4d %5d %4zu-%-4zu | %8.2f %8.2f %8.2f %6.2f | %8.2f %8.2f %8.2f %6.2f\n", run, loops.back(),
                  begin < wall.size() ? begin : 0, end, total_med, *std::max_element(total.begin(), total.end()),
                  window_max(total), window_max(total) / total_med, track_med,
                  *std::max_element(wall.begin(), wall.end()), window_max(wall), window_max(wall) / track_med);
    }
    std::printf("ms per frame, wall clock; frame = frame building + tracking, track = the tracker alone; window: "
                "frames from the loop detection to the end of its global BA; w/med: window max / median "
                "(bar: <= 2)\n");
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_tracking_stall: %s\n", e.what());
    return 1;
  }
  return 0;
}
