// `stillslam bench`: the segmentation on/off benchmark. Runs each sequence N
// times per mode, keeps the median run of each, and writes report.md,
// results.json, plots and every run's trajectory into --out. See
// benchmark/benchmark.h for the conventions and bench/README.md for usage.
#include <spdlog/spdlog.h>

#include <iostream>
#include <memory>

#include "commands.h"
#include "opencv_threads.h"
#include "stillslam/benchmark/benchmark.h"
#include "stillslam/benchmark/report.h"
#include "stillslam/core/error.h"
#include "stillslam/system/system.h"

namespace stillslam::apps {
namespace {

struct BenchArgs {
  std::vector<std::string> sequences;
  std::string list, config, out = "bench_results", vocabulary;
  int runs = 5;
  std::size_t max_frames = 0;
  bool deterministic = false;
  bool raw_trajectory = false;
  int opencv_threads = 1;
};

void run_bench(const BenchArgs& args) {
  std::vector<BenchmarkInput> inputs;
  for (const std::string& s : args.sequences) inputs.push_back({"", s, "", ""});
  if (!args.list.empty()) {
    for (BenchmarkInput& in : read_benchmark_list(args.list)) inputs.push_back(std::move(in));
  }
  if (inputs.empty()) throw Error("bench: give at least one --sequence DIR or a --list FILE");
  if (args.runs < 1) throw Error("bench: --runs must be at least 1");
  // Once for every run, whichever mode runs first (see opencv_threads.h).
  set_opencv_threads(args.opencv_threads);
  BenchmarkOptions options;
  options.runs = args.runs;
  options.deterministic = args.deterministic;
  options.refine_trajectory = !args.raw_trajectory;
  options.vocabulary_path = resolve_vocabulary_option(args.vocabulary);
  if (args.max_frames > 0) options.max_frames = args.max_frames;
  options.output_dir = args.out;
  spdlog::info("bench: {} sequence(s), {} run(s) per mode, results in {}", inputs.size(), args.runs, args.out);
  const std::vector<SequenceResult> results = run_benchmark(inputs, args.config, options);
  const ReportFiles files = write_benchmark_report(args.out, results, options);

  std::cout << "\n" << benchmark_summary_table(results) << "\n";
  std::cout << "ATE = APE rmse (SE3 aligned), RPE per second, median of " << args.runs
            << " run(s) per mode; improvement = (off - on) / off\n";
  std::cout << "report:       " << files.report.string() << "\n";
  std::cout << "results:      " << files.results.string() << "\n";
  std::cout << "plots:        " << args.out << "/<sequence>_{trajectories,ape,rpe}.svg\n";
  if (!files.run_reports.empty()) std::cout << "run reports:  " << args.out << "/<sequence>_seg_{off,on}.html\n";
  std::cout << "trajectories: " << args.out << "/<sequence>/seg_{on,off}/run_<k>/trajectory.txt\n";
  std::size_t failed = 0;
  for (const SequenceResult& r : results) failed += r.error ? 1 : 0;
  if (failed == results.size()) throw Error("bench: no sequence could be benchmarked (see " + files.report.string() + ")");
  if (failed > 0) spdlog::warn("bench: {} of {} sequence(s) could not be benchmarked", failed, results.size());
}

}  // namespace

void add_bench_command(CLI::App& app) {
  auto args = std::make_shared<BenchArgs>();
  CLI::App* cmd = app.add_subcommand(
      "bench", "segmentation on/off benchmark: N runs per mode per sequence, median runs, report.md + results.json");
  cmd->add_option("--sequence", args->sequences,
                  "dataset folder with ground truth (TUM RGB-D, EuRoC or KITTI layout); repeatable");
  cmd->add_option("--list", args->list, "file with one `folder [config [groundtruth]]` per line")
      ->check(CLI::ExistingFile);
  cmd->add_option("--config", args->config, "settings YAML for every sequence (default: settings.yaml in each folder)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--opencv-threads", args->opencv_threads,
                  "OpenCV's thread pool (YOLO and ORB) for every run; 0: OpenCV's default (all cores). Default 1, "
                  "as Segmentation.threads in `stillslam run`")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--runs", args->runs, "runs per mode (the median run by ATE is reported)")->capture_default_str();
  cmd->add_option("--out", args->out, "output folder")->capture_default_str();
  cmd->add_option("--max-frames", args->max_frames, "process at most N frames of each sequence");
  cmd->add_option("--vocabulary", args->vocabulary,
                  "ORB vocabulary for relocalization and loop closing (default: vocab/orb_vocabulary.bin of the "
                  "repository the binary was built in; 'none' disables both)");
  cmd->add_flag("--deterministic", args->deterministic,
                "synchronous local mapping (runs repeat bit for bit, so --runs 1 suffices)");
  cmd->add_flag("--raw-trajectory", args->raw_trajectory, "the poses as tracked, without re-estimating each frame against the final map");
  cmd->callback([args] { run_bench(*args); });
}

}  // namespace stillslam::apps
