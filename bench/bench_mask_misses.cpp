// ATE against the share of frames whose segmentation mask is missed
// (issue #20): a `stillslam simulate` folder's exact masks stand for the
// segmenter (bench/oracle_segmenter.h), and at each rate that share of the
// frames gets no mask, at random (fixed seed) or in whole bursts of seconds.
// Each rate runs --runs times (threaded unless --deterministic), run k with
// the missed frames of seed + k; medians are printed as a table and written
// as JSON. The ratio column is the median ATE
// over the median ATE with no misses (the bar: <= 1.5 at 30 %).
//
//   build/bench/bench_mask_misses --config S.yaml --input SIMDIR [--rates 0,0.1,0.3,0.5]
//       [--burst-seconds 1] [--runs 5] [--seed 1] [--vocabulary FILE] [--deterministic]
//       [--max-frames N] [--json OUT]
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "oracle_segmenter.h"
#include "stillslam/eval/evaluate.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/settings/settings.h"
#include "stillslam/system/dataset_runner.h"

namespace fs = std::filesystem;
using namespace stillslam;

namespace {

struct Args {
  std::string config, input, json, vocabulary;
  std::vector<double> rates{0, 0.1, 0.3, 0.5};
  double burst_seconds = 1;
  int runs = 5;
  std::uint64_t seed = 1;
  bool deterministic = false;
  std::size_t max_frames = 0;
};

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Row {
  std::string mode;  // "frames" or "bursts"
  double rate = 0;
  std::size_t missed = 0;
  std::vector<double> ate;
  std::vector<double> tracked;
};

int run(const Args& a) {
  const Settings settings = load_settings(a.config);
  const auto dataset = open_dataset(a.input, settings);
  const Trajectory gt = read_trajectory(fs::path(a.input) / "groundtruth.txt");
  const std::size_t frames = oracle::oracle_mask_files(a.input).size();

  std::vector<Row> rows;
  for (double rate : a.rates) rows.push_back({"frames", rate, 0, {}, {}});
  if (a.burst_seconds > 0) {
    for (double rate : a.rates) {
      if (rate > 0) rows.push_back({"bursts", rate, 0, {}, {}});
    }
  }
  for (Row& row : rows) {
    oracle::MaskMissOptions misses;
    misses.rate = row.rate;
    misses.burst_seconds = row.mode == "bursts" ? a.burst_seconds : 0;
    misses.fps = settings.fps > 0 ? settings.fps : 30.0;
    // Run k misses the frames of seed + k: deterministic runs would repeat
    // bit for bit on one seed, so they differ by the frames missed; without
    // misses a deterministic run is done once.
    const int runs = a.deterministic && row.rate == 0 ? 1 : a.runs;
    for (int k = 0; k < runs; ++k) {
      misses.seed = a.seed + static_cast<std::uint64_t>(k);
      const std::vector<bool> missed = oracle::choose_missed_frames(frames, misses);
      row.missed = static_cast<std::size_t>(std::count(missed.begin(), missed.end(), true));
      RunOptions options;
      options.system.use_segmentation = true;
      options.system.vocabulary_path = a.vocabulary;
      options.system.deterministic = a.deterministic;
      options.system.segmenter_factory = [dir = a.input, missed] {
        return std::make_unique<oracle::OracleSegmenter>(dir, missed);
      };
      if (a.max_frames > 0) options.max_frames = a.max_frames;
      const RunResult r = run_dataset(settings, *dataset, options);
      if (r.error) std::printf("run ended early: %s\n", r.error->c_str());
      const double ate =
          r.trajectory.empty() ? 0.0 : evaluate(gt, r.trajectory, EvaluationOptions{}).ape_stats.rmse;
      row.ate.push_back(ate);
      row.tracked.push_back(r.frames.empty() ? 0.0 : static_cast<double>(r.trajectory.size()) / r.frames.size());
      std::printf("  %s %.2f run %d: ATE %.5f m, %zu poses\n", row.mode.c_str(), row.rate, k + 1, ate,
                  r.trajectory.size());
      std::fflush(stdout);
    }
  }
  const double base = rows.front().rate == 0 ? median(rows.front().ate) : 0;
  std::printf("%s: exact masks missed on a share of the frames, %d run(s) each, medians\n", a.input.c_str(), a.runs);
  std::printf("  %-7s %6s %7s %12s %8s %9s\n", "misses", "rate", "frames", "ATE m", "ratio", "tracked");
  nlohmann::json out;
  out["input"] = a.input;
  out["runs"] = a.runs;
  out["seed"] = a.seed;
  out["burst_seconds"] = a.burst_seconds;
  for (const Row& row : rows) {
    const double m = median(row.ate);
    const double ratio = base > 0 ? m / base : 0;
    std::printf("  %-7s %6.2f %7zu %12.5f %8.2f %8.1f%%\n", row.mode.c_str(), row.rate, row.missed, m, ratio,
                100 * median(row.tracked));
    out["rows"].push_back({{"mode", row.mode},
                           {"rate", row.rate},
                           {"missed_frames", row.missed},
                           {"ate_median", m},
                           {"ate_runs", row.ate},
                           {"ratio_to_no_misses", ratio},
                           {"tracked_median", median(row.tracked)}});
  }
  if (!a.json.empty()) std::ofstream(a.json) << out.dump(1) << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  CLI::App app("ATE against missed segmentation masks (see bench/bench_mask_misses.cpp)", "bench_mask_misses");
  app.add_option("--config", a.config, "settings YAML")->required();
  app.add_option("--input", a.input, "a `stillslam simulate` folder (masks/, groundtruth.txt)")->required();
  app.add_option("--rates", a.rates, "shares of frames without a mask")->delimiter(',')->check(CLI::Range(0.0, 1.0));
  app.add_option("--burst-seconds", a.burst_seconds, "also miss in bursts of this length (0: no burst rows)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--runs", a.runs, "runs per rate (medians)")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--seed", a.seed, "seed of the missed frames")->capture_default_str();
  app.add_option("--vocabulary", a.vocabulary, "ORB vocabulary (relocalization, loop closing; default: none)");
  app.add_flag("--deterministic", a.deterministic, "synchronous local mapping");
  app.add_option("--max-frames", a.max_frames, "stop after N frames (0: all)")->capture_default_str();
  app.add_option("--json", a.json, "write the table as JSON here");
  CLI11_PARSE(app, argc, argv);
  try {
    return run(a);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_mask_misses: %s\n", e.what());
    return 1;
  }
}
