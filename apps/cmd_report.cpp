// `stillslam report RUN_DIR [--compare RUN_DIR2 ...] [--gt FILE] --out FILE.html`:
// one self-contained HTML report of a run folder (benchmark/run_report.h).
#include <iostream>
#include <memory>

#include "commands.h"
#include "stillslam/benchmark/run_report.h"

namespace stillslam::apps {

void add_report_command(CLI::App& app) {
  auto options = std::make_shared<RunReportOptions>();
  auto main_run = std::make_shared<std::string>();
  auto compare = std::make_shared<std::vector<std::string>>();
  auto groundtruth = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "report", "one self-contained HTML report of a run folder (trajectory, errors, timing, masks, frames, settings)");
  cmd->add_option("run_dir", *main_run, "the --output folder of `stillslam run` (or a bench run folder)")->required();
  cmd->add_option("--compare", *compare, "more run folders overlaid on the same figures (e.g. --no-segmentation)");
  cmd->add_option("--gt", *groundtruth,
                  "ground truth (TUM, EuRoC or KITTI); default: the file the run used (stats.json \"groundtruth\") or "
                  "groundtruth.txt in its input folder");
  cmd->add_option("--out", *out, "the HTML file to write")->required();
  cmd->add_option("--strip-frames", options->strip_frames, "saved frames shown per run (0: none)")
      ->capture_default_str();
  cmd->callback([=] {
    options->runs = {*main_run};
    for (const std::string& dir : *compare) options->runs.emplace_back(dir);
    options->groundtruth = *groundtruth;
    options->out = *out;
    const std::optional<double> ate = write_run_report(*options);
    std::cout << "wrote " << *out;
    if (ate) std::cout << " (ATE rmse " << *ate << " m)";
    std::cout << "\n";
  });
}

}  // namespace stillslam::apps
