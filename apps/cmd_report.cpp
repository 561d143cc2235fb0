// `stillslam report RUN_DIR [--compare RUN_DIR2 ...] [--gt FILE] --out FILE.html`:
// one self-contained HTML report of a run folder (benchmark/run_report.h).
#include <iostream>
#include <memory>

#include "commands.h"
#include "stillslam/benchmark/run_report.h"

namespace stillslam::apps {
namespace {

struct ReportArgs {
  std::string run_dir, groundtruth, out;
  std::vector<std::string> compare;
  int strip_frames = RunReportOptions{}.strip_frames;
};

void report(const ReportArgs& args) {
  RunReportOptions options;
  options.runs = {args.run_dir};
  for (const std::string& dir : args.compare) options.runs.emplace_back(dir);
  options.groundtruth = args.groundtruth;
  options.out = args.out;
  options.strip_frames = args.strip_frames;
  const std::optional<double> ate = write_run_report(options);
  std::cout << "wrote " << args.out;
  if (ate) std::cout << " (ATE rmse " << *ate << " m)";
  std::cout << "\n";
}

}  // namespace

void add_report_command(CLI::App& app) {
  auto args = std::make_shared<ReportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "report", "one self-contained HTML report of a run folder (trajectory, errors, timing, masks, frames, settings)");
  cmd->add_option("run_dir", args->run_dir, "the --output folder of `stillslam run` (or a bench run folder)")
      ->required();
  cmd->add_option("--compare", args->compare, "more run folders overlaid on the same figures (e.g. --no-segmentation)");
  cmd->add_option("--gt", args->groundtruth,
                  "ground truth (TUM, EuRoC or KITTI); default: the file the run used (stats.json \"groundtruth\") or "
                  "groundtruth.txt in its input folder");
  cmd->add_option("--out", args->out, "the HTML file to write")->required();
  cmd->add_option("--strip-frames", args->strip_frames, "saved frames shown per run (0: none)")->capture_default_str();
  cmd->callback([args] { report(*args); });
}

}  // namespace stillslam::apps
