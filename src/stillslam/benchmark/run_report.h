#pragma once
// `stillslam report`: one self-contained HTML file (inline CSS, JS and SVG,
// images as data URIs; nothing loaded from the network) about one run folder
// of `stillslam run` (or of `bench`), optionally overlaid with others
// (--compare): trajectories against ground truth from above and in an
// orbitable 3D view, APE and RPE over time, per-frame time stacked by stage,
// features removed and mask coverage per frame, tracking losses and
// relocalizations on a timeline, a strip of the run's saved frames
// (--save-frames), the settings used, and a summary whose numbers carry ids
// (ate-rmse-<k>, frames-<k>, … for run k, 0 = the main run) for scripts.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stillslam/eval/evaluate.h"
#include "stillslam/io/trajectory.h"

namespace stillslam {

struct RunReportOptions {
  std::vector<std::filesystem::path> runs;  // run folders; the first is the main run
  // Ground truth file; empty: the one the main run recorded in stats.json
  // ("groundtruth"), else <input>/groundtruth.txt of its stats.json "input".
  std::filesystem::path groundtruth;
  std::filesystem::path out;  // the HTML file
  int strip_frames = 8;       // saved frames shown per run, evenly spaced
  int strip_width = 320;      // pixels each, re-encoded as JPEG
  void check() const;
};

// One run folder as the report reads it.
struct ReportRun {
  std::filesystem::path dir;
  std::string label;          // folder name and segmentation on/off
  nlohmann::json stats;       // stats.json
  Trajectory trajectory;      // trajectory.txt
  std::size_t keyframes = 0;  // lines of keyframes.txt (0 when absent)
  std::vector<std::filesystem::path> saved_frames;  // PNG/JPEG of --save-frames, by name
  std::optional<EvaluationResult> evaluation;       // against the ground truth
  std::string evaluation_error;
};

// Reads DIR/stats.json and DIR/trajectory.txt (Error naming the file and the
// fix when either is missing or malformed) and finds the saved frames: the
// folder stats.json names under saved_frames.dir, else DIR/frames.
ReportRun load_report_run(const std::filesystem::path& dir);

// The ground truth file the report uses (see RunReportOptions::groundtruth); none when unknown.
std::optional<std::filesystem::path> report_groundtruth_path(const RunReportOptions& options, const ReportRun& main);

// Evaluates each run against `groundtruth` as `stillslam eval` does by
// default (greedy association, SE3 alignment, 1-frame RPE); a run that cannot
// be evaluated keeps the reason in evaluation_error.
void evaluate_report_runs(std::vector<ReportRun>& runs, const Trajectory& groundtruth);

// The HTML document.
std::string render_run_report(const std::vector<ReportRun>& runs, const Trajectory& groundtruth,
                              const std::string& groundtruth_name, const RunReportOptions& options);

// Loads, evaluates and writes options.out (whole or not at all). Returns the
// main run's ATE rmse when it could be evaluated.
std::optional<double> write_run_report(const RunReportOptions& options);

}  // namespace stillslam
