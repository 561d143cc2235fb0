#include "stillslam/benchmark/run_report.h"

#include <algorithm>
#include <fstream>

#include "stillslam/core/error.h"
#include "stillslam/core/option_check.h"
#include "stillslam/core/text_file.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

std::string run_label(const fs::path& dir, const nlohmann::json& stats) {
  const fs::path normal = dir.lexically_normal();
  fs::path name = normal.filename().empty() ? normal.parent_path().filename() : normal.filename();
  // A bench run folder <sequence>/seg_on/run_1 reads better with its parents.
  if (name.string().rfind("run_", 0) == 0) {
    const fs::path parent = (normal.filename().empty() ? normal.parent_path() : normal).parent_path();
    name = parent.parent_path().filename() / parent.filename() / name;
  }
  std::string label = name.string();
  if (stats.contains("segmentation") && stats["segmentation"].is_boolean()) {
    label += stats["segmentation"].get<bool>() ? " (segmentation on)" : " (segmentation off)";
  }
  return label;
}

std::size_t count_pose_lines(const fs::path& path) {
  std::ifstream in(path);
  std::size_t n = 0;
  std::string line;
  while (std::getline(in, line)) n += !line.empty() && line[0] != '#' ? 1 : 0;
  return n;
}

std::vector<fs::path> list_saved_frames(const fs::path& folder) {
  std::vector<fs::path> files;
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return files;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
    const std::string ext = e.path().extension().string();
    if (e.is_regular_file() && (ext == ".png" || ext == ".jpg" || ext == ".jpeg")) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

void RunReportOptions::check() const {
  using namespace option_check;
  if (runs.empty()) throw Error("report: give a run folder (the --output of `stillslam run`)");
  if (out.empty()) throw Error("report: give the HTML file to write with --out FILE.html");
  in_range("--strip-frames", strip_frames, 0, 100);
  in_range("RunReportOptions.strip_width", strip_width, 32, 2000);
}

ReportRun load_report_run(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw Error("report: run folder " + dir.string() + " does not exist; give the --output folder of `stillslam run`");
  }
  ReportRun run;
  run.dir = dir;
  const fs::path stats_path = dir / "stats.json";
  std::ifstream stats_file(stats_path);
  if (!stats_file) {
    throw Error("report: " + stats_path.string() + " is missing; is " + dir.string() +
                " the --output folder of a finished `stillslam run`?");
  }
  try {
    run.stats = nlohmann::json::parse(stats_file);
  } catch (const nlohmann::json::exception& e) {
    throw Error("report: " + stats_path.string() + " is not valid JSON (" + e.what() + "); run again to rewrite it");
  }
  if (!run.stats.is_object() || !run.stats.contains("frames") || !run.stats["frames"].is_array()) {
    throw Error("report: " + stats_path.string() + " has no \"frames\" array; it was not written by `stillslam run`");
  }
  const fs::path trajectory_path = dir / "trajectory.txt";
  if (!fs::exists(trajectory_path, ec)) {
    throw Error("report: " + trajectory_path.string() + " is missing; is " + dir.string() +
                " the --output folder of a finished `stillslam run`?");
  }
  // A run stopped before its first tracked frame leaves an empty trajectory.txt: still a report.
  if (count_pose_lines(trajectory_path) > 0) run.trajectory = read_trajectory(trajectory_path);
  run.keyframes = count_pose_lines(dir / "keyframes.txt");
  run.label = run_label(dir, run.stats);
  fs::path frames_dir = dir / "frames";
  if (const auto saved = run.stats.find("saved_frames"); saved != run.stats.end() && saved->contains("dir")) {
    const fs::path recorded = (*saved)["dir"].get<std::string>();
    if (fs::is_directory(recorded, ec)) frames_dir = recorded;
  }
  run.saved_frames = list_saved_frames(frames_dir);
  return run;
}

std::optional<fs::path> report_groundtruth_path(const RunReportOptions& options, const ReportRun& main) {
  if (!options.groundtruth.empty()) return options.groundtruth;
  std::error_code ec;
  if (const auto gt = main.stats.find("groundtruth"); gt != main.stats.end() && gt->is_string()) {
    if (fs::exists(gt->get<std::string>(), ec)) return fs::path(gt->get<std::string>());
  }
  if (const auto input = main.stats.find("input"); input != main.stats.end() && input->is_string()) {
    const fs::path candidate = fs::path(input->get<std::string>()) / "groundtruth.txt";
    if (fs::exists(candidate, ec)) return candidate;
  }
  return std::nullopt;
}

void evaluate_report_runs(std::vector<ReportRun>& runs, const Trajectory& groundtruth) {
  for (ReportRun& run : runs) {
    if (groundtruth.empty()) {
      run.evaluation_error = "no ground truth (pass --gt FILE)";
    } else if (run.trajectory.empty()) {
      run.evaluation_error = "no tracked frame";
    } else {
      try {
        run.evaluation = evaluate(groundtruth, run.trajectory, EvaluationOptions{});
      } catch (const Error& e) {
        run.evaluation_error = e.what();
      }
    }
  }
}

std::optional<double> write_run_report(const RunReportOptions& options) {
  options.check();
  std::vector<ReportRun> runs;
  for (const fs::path& dir : options.runs) runs.push_back(load_report_run(dir));
  Trajectory groundtruth;
  std::string groundtruth_name;
  if (const auto gt_path = report_groundtruth_path(options, runs.front())) {
    groundtruth = read_trajectory(*gt_path);  // an Error names the file
    groundtruth_name = gt_path->string();
  }
  evaluate_report_runs(runs, groundtruth);
  std::string html;
  try {
    html = render_run_report(runs, groundtruth, groundtruth_name, options);
  } catch (const nlohmann::json::exception& e) {
    // A stats.json edited by hand or written by another tool: a value of the wrong type.
    std::string dirs;
    for (const ReportRun& r : runs) dirs += (dirs.empty() ? "" : ", ") + (r.dir / "stats.json").string();
    throw Error("report: unexpected value in " + dirs + " (" + e.what() + "); run again to rewrite it");
  }
  write_text_file(options.out, html);
  if (!runs.front().evaluation) return std::nullopt;
  return runs.front().evaluation->ape_stats.rmse;
}

}  // namespace stillslam
