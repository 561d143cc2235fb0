// What one YOLO segmentation costs on a render's own frames and settings, per
// OpenCV thread-pool size, measured side by side: the pool sizes take turns
// call by call, so load from other processes hits them alike. Wall time is
// what a mask waits; process CPU time is what it takes from the cores the
// tracker and the mapper share (the budget on 2 cores at 30 Hz is 66 CPU-ms
// per frame in all).
//
//   build/bench/bench_yolo_cost --config SEQ/settings.yaml --input SEQ [--frames N (40)]
//       [--threads 1,2] [--rounds R (3)] [--intervals 3,4,5,6]
//
// The frames are decoded before timing. --intervals prints the segmenter's
// CPU per processed frame when it runs on every Nth frame.
#include <CLI/CLI.hpp>
#include <opencv2/core.hpp>

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "load_average.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/core/thread_cpu_stopwatch.h"
#include "stillslam/io/dataset.h"
#include "stillslam/segmentation/yolo_segmenter.h"
#include "stillslam/settings/settings.h"
#include "stillslam/system/process_cpu_time.h"

using namespace stillslam;

namespace {

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / static_cast<double>(v.size());
}

struct Costs {
  std::vector<double> wall, process_cpu, thread_cpu;
};

}  // namespace

int main(int argc, char** argv) {
  std::string config, input;
  int frames = 40, rounds = 3;
  std::vector<int> threads{1, 2}, intervals{3, 4, 5, 6};
  CLI::App app("YOLO cost per call by thread-pool size (see the comment at the top of bench/bench_yolo_cost.cpp)",
               "bench_yolo_cost");
  app.add_option("--config", config, "settings YAML (Segmentation.*: model, classes, thresholds)")->required();
  app.add_option("--input", input, "dataset folder")->required();
  app.add_option("--frames", frames, "frames spread over the sequence")->check(CLI::PositiveNumber);
  app.add_option("--rounds", rounds, "passes over the frames")->check(CLI::PositiveNumber);
  app.add_option("--threads", threads, "OpenCV pool sizes to compare")->delimiter(',')->check(CLI::PositiveNumber);
  app.add_option("--intervals", intervals, "segmentation intervals to cost")->delimiter(',')->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  try {
    const Settings settings = load_settings(config);
    const auto dataset = open_dataset(input, settings);
    std::vector<cv::Mat> images;
    const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(frames), dataset->size());
    for (std::size_t k = 0; k < n; ++k) images.push_back(dataset->load(k * dataset->size() / n).color);
    YoloSegmenter segmenter(settings.segmentation);
    const double load_start = load_average();
    std::map<int, Costs> costs;
    for (int r = 0; r <= rounds; ++r) {  // round 0 warms up
      for (const cv::Mat& image : images) {
        for (int t : threads) {
          cv::setNumThreads(t);
          const double p0 = process_cpu_seconds();
          const ThreadCpuStopwatch thread_cpu;
          Stopwatch wall;
          segmenter.segment(image);
          if (r == 0) continue;
          costs[t].wall.push_back(wall.elapsed_ms());
          costs[t].process_cpu.push_back(1e3 * (process_cpu_seconds() - p0));
          costs[t].thread_cpu.push_back(thread_cpu.elapsed_ms());
        }
      }
    }
    const cv::Size in = segmenter.input_size();
    std::printf("%s, model input %dx%d, %zu frames x %d rounds, load average %.1f at start, %.1f at end\n",
                settings.segmentation.model_path.c_str(), in.height, in.width, images.size(), rounds, load_start,
                load_average());
    std::printf("%8s %10s %10s %10s %12s %12s %12s\n", "threads", "wall p50", "wall p90", "wall mean", "proc CPU p50",
                "proc CPU mean", "call-thread");
    for (int t : threads) {
      const Costs& c = costs[t];
      std::printf("%8d %10.1f %10.1f %10.1f %12.1f %12.1f %12.1f\n", t, quantile(c.wall, 0.5), quantile(c.wall, 0.9),
                  mean(c.wall), quantile(c.process_cpu, 0.5), mean(c.process_cpu), quantile(c.thread_cpu, 0.5));
    }
    std::printf("segmenter CPU ms per processed frame (mean process CPU / interval):\n%8s", "threads");
    for (int i : intervals) std::printf(" %9s%-2d", "every ", i);
    std::printf("\n");
    for (int t : threads) {
      std::printf("%8d", t);
      for (int i : intervals) std::printf(" %11.1f", mean(costs[t].process_cpu) / i);
      std::printf("\n");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_yolo_cost: %s\n", e.what());
    return 1;
  }
  return 0;
}
