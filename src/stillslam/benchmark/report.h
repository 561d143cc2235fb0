#pragma once
// The outputs of `stillslam bench`: report.md (paper-style tables, baseline =
// segmentation off vs ours = segmentation on, median runs), results.json
// (every number of every run) and per-sequence SVG plots next to the report.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stillslam/benchmark/benchmark.h"

namespace stillslam {

// results.json: {"benchmark": {...conventions...}, "sequences": [{name, folder,
// config, groundtruth, dataset, sensor, frames, error?, "off": mode, "on": mode,
// "improvement_percent": {...}}]}; a mode holds segmentation, segmentation_active,
// median_run (1-based, null when there is none) and runs [{run, error?,
// frames, tracked, lost_frames, lost_episodes, keyframes, times_ms{...},
// wall_seconds, trajectory, accuracy{pairs, ape{...}, rpe_trans{...}, rpe_rot{...},
// rpe_trans_1s{...}, rpe_rot_1s{...}} | evaluation_error}].
nlohmann::json benchmark_to_json(const std::vector<SequenceResult>& results, const BenchmarkOptions& options);

// The main comparison (one row per sequence, median runs): ATE rmse, RPE per
// second, time per frame, tracked frames and losses, off vs on with the
// improvement. A Markdown table that also reads well on a terminal.
std::string benchmark_summary_table(const std::vector<SequenceResult>& results);

// The figures of one sequence written by write_sequence_plots (relative to the report).
struct SequencePlots {
  std::filesystem::path trajectories, ape, rpe;
};

// <dir>/<name>_trajectories.svg (ground truth and both median runs, aligned),
// <name>_ape.svg (APE over time) and <name>_rpe.svg (translational RPE per
// second over time; per frame when the sequence is shorter than 1 s).
// Plots of a mode without an evaluated median run are left out of the figures.
SequencePlots write_sequence_plots(const std::filesystem::path& dir, const SequenceResult& result);

std::string benchmark_markdown(const std::vector<SequenceResult>& results, const BenchmarkOptions& options,
                               const std::vector<SequencePlots>& plots);

struct ReportFiles {
  std::filesystem::path report, results;
  std::vector<std::filesystem::path> run_reports;  // <sequence>_seg_{off,on}.html
};
// Writes report.md, results.json and the plots into `dir` (created); with run
// folders (options.output_dir) also one HTML run report per sequence and
// mode (run_report.h), linked from report.md.
ReportFiles write_benchmark_report(const std::filesystem::path& dir, const std::vector<SequenceResult>& results,
                                   const BenchmarkOptions& options);

}  // namespace stillslam
