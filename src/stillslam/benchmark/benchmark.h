#pragma once
// The segmentation on/off benchmark behind `stillslam bench`: every sequence
// is run N times with the dynamic-object masks and N times without them on
// identical settings (in-process, no realtime pacing), each run is evaluated
// against ground truth, and the median run of each mode (by APE rmse) is the
// one the report compares, as in the DynaSLAM-style paper tables.
//
// Nothing here throws for a bad sequence or a failing run: the problem is
// recorded (SequenceResult::error, RunRecord::error) and the benchmark goes on.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "stillslam/benchmark/benchmark_input.h"
#include "stillslam/eval/error_statistics.h"
#include "stillslam/eval/evaluate.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/system/run_summary.h"

namespace stillslam {

struct BenchmarkOptions {
  int runs = 5;  // per mode
  std::optional<std::size_t> max_frames;
  bool deterministic = false;  // synchronous local mapping (runs then repeat exactly)
  // Relocalization and loop closing (SystemOptions::vocabulary_path); empty: off.
  std::filesystem::path vocabulary_path;
  bool loop_closing = true;
  bool refine_trajectory = true;  // SystemOptions::trajectory_refinement
  // Each run's trajectory.txt / keyframes.txt go to
  // <output_dir>/<sequence>/seg_{on,off}/run_<k>/. Empty: not written.
  std::filesystem::path output_dir;
};

// The evaluation conventions of the report (see benchmark.cpp for why):
// APE: translation after SE3 (Horn) alignment, TUM greedy association 0.02 s.
// RPE per frame: consecutive 1-frame steps of the associated sequence.
// RPE per second: every start pose with its pose 1 s later (TUM evaluate_rpe.py
// with --fixed_delta --delta 1 --delta_unit s), i.e. drift in m/s and deg/s.
EvaluationOptions benchmark_ape_options();
PosePairOptions rpe_per_second_pairs();

struct AccuracyStats {
  std::size_t pairs = 0;  // associated poses
  ErrorStatistics ape;                        // m
  ErrorStatistics rpe_trans, rpe_rot;         // per frame: m, deg
  ErrorStatistics rpe_trans_1s, rpe_rot_1s;   // per second: m, deg
};
// Throws Error when nothing associates or alignment is impossible.
AccuracyStats evaluate_accuracy(const Trajectory& groundtruth, const Trajectory& estimate);

struct RunRecord {
  int run = 0;  // 1-based within its mode
  bool segmentation = false;
  std::optional<std::string> error;  // what ended the run (exception or input error)
  std::size_t frames = 0, tracked = 0, lost_frames = 0, lost_episodes = 0, keyframes = 0;
  TimingSummary total_ms;         // per frame: frame building + tracking (the tracking thread)
  TimingSummary tracker_ms;       // the tracker alone
  TimingSummary segmentation_ms;  // segmenter per frame, on its own thread (frames it ran on)
  TimingSummary segmentation_wait_ms;
  double wall_seconds = 0;
  LocalBundleAdjustmentSummary local_ba;  // local BA times, aborted share, windows, mapping CPU per frame
  std::optional<AccuracyStats> accuracy;  // absent when the run could not be evaluated
  std::optional<std::string> evaluation_error;
  std::filesystem::path trajectory_file;  // empty when not written
  Trajectory trajectory;
  bool failed() const { return error.has_value() || !accuracy.has_value(); }
};

struct ModeResult {
  bool segmentation = false;
  // Segmentation actually ran (requested and Segmentation.enabled in the settings).
  bool segmentation_active = false;
  std::vector<RunRecord> runs;
  std::optional<std::size_t> median;  // index into runs
  const RunRecord* median_run() const { return median ? &runs[*median] : nullptr; }
};

struct SequenceResult {
  BenchmarkInput input;  // with the config and ground truth actually used
  std::string dataset_kind, sensor;
  std::size_t dataset_frames = 0;
  std::optional<std::string> error;  // the sequence could not be benchmarked at all
  Trajectory groundtruth;
  ModeResult off, on;
};

// The median run by APE rmse: failed runs rank after every evaluated one (so
// failures push the median towards them rather than being hidden), ties keep
// run order, and with an even count the lower middle run is taken (the better
// of the two middle runs; with 2 runs that is the better one).
std::optional<std::size_t> select_median_run(const std::vector<RunRecord>& runs);

// (off - on) / off in percent; NaN when off is not positive or either is not finite.
double improvement_percent(double off, double on);

// Frames in the Lost state, and how many separate stretches of them.
std::size_t count_lost_frames(const std::vector<FrameStats>& frames);
std::size_t count_lost_episodes(const std::vector<FrameStats>& frames);

// Runs one sequence `options.runs` times per mode (off first, then on).
// `input` must be resolved (resolve_benchmark_input).
SequenceResult benchmark_sequence(const BenchmarkInput& input, const BenchmarkOptions& options);

// Names and resolves the inputs (default_config: --config, may be empty) and
// benchmarks each in turn; an input that cannot be resolved is recorded.
std::vector<SequenceResult> run_benchmark(std::vector<BenchmarkInput> inputs,
                                          const std::filesystem::path& default_config,
                                          const BenchmarkOptions& options);

}  // namespace stillslam
