#include "stillslam/benchmark/benchmark.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <numeric>

#include "stillslam/core/error.h"
#include "stillslam/core/json_text.h"
#include "stillslam/core/text_file.h"
#include "stillslam/eval/metrics.h"
#include "stillslam/io/dataset.h"
#include "stillslam/settings/settings.h"
#include "stillslam/system/run_result_json.h"
#include "stillslam/system/dataset_runner.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

// The statistics over the frames where the value was measured (> 0), so a
// mode without segmentation reports zeros rather than a diluted mean.
TimingSummary summarize_positive(const std::vector<FrameStats>& frames, double (*get)(const FrameStats&)) {
  std::vector<double> v;
  for (const FrameStats& f : frames) {
    if (const double x = get(f); x > 0) v.push_back(x);
  }
  return summarize_times(std::move(v));
}

// What `stillslam report` reads from a run folder, as `stillslam run` writes it.
void write_run_files(const fs::path& dir, const RunResult& result, const BenchmarkInput& input,
                     const std::vector<std::size_t>& features_removed, RunRecord& record) {
  fs::create_directories(dir);
  record.trajectory_file = dir / "trajectory.txt";
  write_trajectory(record.trajectory_file, result.trajectory);
  write_trajectory(dir / "keyframes.txt", result.keyframes);
  nlohmann::json stats = run_result_json(result, features_removed);
  stats["config"] = fs::absolute(input.config).string();
  stats["input"] = fs::absolute(input.folder).string();
  if (!input.groundtruth.empty()) stats["groundtruth"] = fs::absolute(input.groundtruth).string();
  stats["segmentation"] = record.segmentation;
  write_text_file(dir / "stats.json", json_text(stats, 1) + "\n");  // whole or not at all; an Error names the cause
}

RunRecord run_once(const Settings& settings, const Dataset& dataset, const BenchmarkInput& input,
                   const Trajectory& groundtruth, bool segmentation, int run, const BenchmarkOptions& options,
                   const fs::path& run_dir, bool& segmentation_active) {
  RunRecord record;
  record.run = run;
  record.segmentation = segmentation;
  RunOptions ro;
  ro.system.use_segmentation = segmentation;
  ro.system.deterministic = options.deterministic;
  ro.system.vocabulary_path = options.vocabulary_path;
  ro.system.loop_closing = options.loop_closing;
  ro.system.trajectory_refinement.enabled = options.refine_trajectory;
  ro.max_frames = options.max_frames;
  ro.realtime = false;
  std::vector<std::size_t> features_removed;  // per frame, from the published snapshot
  ro.on_frame = [&segmentation_active, &features_removed](const FrameStats&, const System& system) {
    segmentation_active = system.segmentation_enabled();
    const std::shared_ptr<const FrameSnapshot> frame = system.publisher().frame().value;
    features_removed.push_back(frame ? frame->removed_keypoints.size() : 0);
  };
  RunResult result;
  try {
    result = run_dataset(settings, dataset, ro);
  } catch (const std::exception& e) {
    record.error = e.what();
    return record;
  }
  record.error = result.error;
  record.frames = result.frames.size();
  record.wall_seconds = result.wall_seconds;
  const RunSummary summary = summarize_run(result.frames);
  record.tracked = summary.tracked;
  record.keyframes = result.keyframes.size();
  record.lost_frames = count_lost_frames(result.frames);
  record.lost_episodes = count_lost_episodes(result.frames);
  record.total_ms = summary.total_ms;
  record.tracker_ms = summary.tracking_ms;
  record.segmentation_ms = summarize_positive(result.frames, [](const FrameStats& f) { return f.build.segmentation_ms; });
  record.segmentation_wait_ms = summary.segmentation_wait_ms;
  record.local_ba = summarize_local_bundle_adjustment(result.mapper, result.frames.size(), sequence_seconds(result.frames));
  record.trajectory = result.trajectory;
  if (!run_dir.empty()) {
    try {
      write_run_files(run_dir, result, input, features_removed, record);
    } catch (const std::exception& e) {
      spdlog::warn("bench: cannot write the files of run {}: {}", run, e.what());
    }
  }
  if (result.trajectory.empty()) {
    record.evaluation_error = "no tracked frame";
  } else {
    try {
      record.accuracy = evaluate_accuracy(groundtruth, result.trajectory);
    } catch (const std::exception& e) {
      record.evaluation_error = e.what();
    }
  }
  return record;
}

}  // namespace

EvaluationOptions benchmark_ape_options() {
  EvaluationOptions o;
  o.alignment = AlignmentType::Se3;
  o.association.method = AssociationMethod::Greedy;
  o.rpe.delta = 1;
  o.rpe.unit = DeltaUnit::Frames;
  o.rpe.all_pairs = false;
  return o;
}

PosePairOptions rpe_per_second_pairs() {
  PosePairOptions p;
  p.delta = 1;
  p.unit = DeltaUnit::Seconds;
  p.all_pairs = true;
  return p;
}

AccuracyStats evaluate_accuracy(const Trajectory& groundtruth, const Trajectory& estimate) {
  const EvaluationResult ev = evaluate(groundtruth, estimate, benchmark_ape_options());
  AccuracyStats a;
  a.pairs = ev.pairs;
  a.ape = ev.ape_stats;
  a.rpe_trans = ev.rpe_trans_stats;
  a.rpe_rot = ev.rpe_rot_stats;
  // Per-second drift on the same associated, aligned sequence; pairs are
  // chosen on the ground truth's stamps as evo and the TUM tool do.
  const std::vector<PosePair> pairs = select_pose_pairs(ev.gt, rpe_per_second_pairs());
  const RelativeErrors rel = relative_errors(ev.gt, ev.est_aligned, pairs);
  a.rpe_trans_1s = compute_statistics(rel.translation);
  a.rpe_rot_1s = compute_statistics(rel.rotation_deg);
  return a;
}

std::optional<std::size_t> select_median_run(const std::vector<RunRecord>& runs) {
  if (runs.empty()) return std::nullopt;
  std::vector<std::size_t> order(runs.size());
  std::iota(order.begin(), order.end(), 0);
  auto key = [&runs](std::size_t i) {
    return runs[i].failed() ? std::numeric_limits<double>::infinity() : runs[i].accuracy->ape.rmse;
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  return order[(order.size() - 1) / 2];
}

double improvement_percent(double off, double on) {
  if (!std::isfinite(off) || !std::isfinite(on) || off <= 0) return std::numeric_limits<double>::quiet_NaN();
  return 100.0 * (off - on) / off;
}

std::size_t count_lost_frames(const std::vector<FrameStats>& frames) {
  return static_cast<std::size_t>(std::count_if(frames.begin(), frames.end(),
                                                [](const FrameStats& f) { return f.state == TrackingState::Lost; }));
}

std::size_t count_lost_episodes(const std::vector<FrameStats>& frames) {
  std::size_t episodes = 0;
  bool lost = false;
  for (const FrameStats& f : frames) {
    const bool now = f.state == TrackingState::Lost;
    if (now && !lost) ++episodes;
    lost = now;
  }
  return episodes;
}

SequenceResult benchmark_sequence(const BenchmarkInput& input, const BenchmarkOptions& options) {
  SequenceResult out;
  out.input = input;
  out.off.segmentation = false;
  out.on.segmentation = true;
  Settings settings;
  std::unique_ptr<Dataset> dataset;
  try {
    settings = load_settings(input.config);
    dataset = open_dataset(input.folder, settings);
    out.groundtruth = load_groundtruth(input.groundtruth, input.folder);
  } catch (const std::exception& e) {
    out.error = e.what();
    spdlog::error("bench {}: {}", input.name, e.what());
    return out;
  }
  out.dataset_kind = dataset->kind();
  out.sensor = to_string(dataset->sensor());
  out.dataset_frames = dataset->size();
  const int runs = std::max(options.runs, 1);
  for (ModeResult* mode : {&out.off, &out.on}) {
    const std::string mode_name = mode->segmentation ? "on" : "off";
    for (int k = 1; k <= runs; ++k) {
      fs::path run_dir;
      if (!options.output_dir.empty()) {
        run_dir = options.output_dir / input.name / ("seg_" + mode_name) / ("run_" + std::to_string(k));
      }
      bool active = false;
      RunRecord r = run_once(settings, *dataset, input, out.groundtruth, mode->segmentation, k, options, run_dir, active);
      mode->segmentation_active = mode->segmentation_active || active;
      if (r.error) {
        spdlog::warn("bench {} seg {} run {}/{}: failed: {}", input.name, mode_name, k, runs, *r.error);
      } else if (r.accuracy) {
        spdlog::info("bench {} seg {} run {}/{}: ATE rmse {:.4f} m, tracked {}/{}, {:.1f} ms/frame", input.name,
                     mode_name, k, runs, r.accuracy->ape.rmse, r.tracked, r.frames, r.total_ms.mean);
      } else {
        spdlog::warn("bench {} seg {} run {}/{}: not evaluated: {}", input.name, mode_name, k, runs,
                     r.evaluation_error.value_or("?"));
      }
      mode->runs.push_back(std::move(r));
    }
    mode->median = select_median_run(mode->runs);
  }
  return out;
}

std::vector<SequenceResult> run_benchmark(std::vector<BenchmarkInput> inputs, const fs::path& default_config,
                                          const BenchmarkOptions& options) {
  name_benchmark_inputs(inputs);
  std::vector<SequenceResult> results;
  for (const BenchmarkInput& input : inputs) {
    BenchmarkInput resolved;
    try {
      resolved = resolve_benchmark_input(input, default_config);
    } catch (const std::exception& e) {
      SequenceResult failed;
      failed.input = input;
      failed.error = e.what();
      spdlog::error("bench {}: {}", input.name, e.what());
      results.push_back(std::move(failed));
      continue;
    }
    results.push_back(benchmark_sequence(resolved, options));
  }
  return results;
}

}  // namespace stillslam
