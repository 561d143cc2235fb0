#include "stillslam/benchmark/report.h"

#include <spdlog/spdlog.h>

#include <fstream>

#include "stillslam/core/error.h"
#include "stillslam/core/json_text.h"
#include "stillslam/core/text_file.h"
#include "stillslam/benchmark/run_report.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

// <dir>/<sequence>_seg_<mode>.html for each mode's median run, with the other
// mode's median run overlaid; returns the Markdown section linking them.
std::string write_mode_reports(const fs::path& dir, const std::vector<SequenceResult>& results,
                               std::vector<fs::path>& written) {
  std::string rows;
  for (const SequenceResult& r : results) {
    if (r.error) continue;
    std::string row = "| " + r.input.name + " |";
    for (const ModeResult* mode : {&r.off, &r.on}) {
      const ModeResult* other = mode == &r.off ? &r.on : &r.off;
      const RunRecord* run = mode->median_run();
      const std::string name = r.input.name + (mode->segmentation ? "_seg_on.html" : "_seg_off.html");
      if (run == nullptr || run->trajectory_file.empty()) {
        row += " – |";
        continue;
      }
      RunReportOptions options;
      options.runs = {run->trajectory_file.parent_path()};
      if (const RunRecord* o = other->median_run(); o != nullptr && !o->trajectory_file.empty()) {
        options.runs.push_back(o->trajectory_file.parent_path());
      }
      options.groundtruth = r.input.groundtruth;
      options.out = dir / name;
      try {
        write_run_report(options);
        written.push_back(options.out);
        row += " [" + name + "](" + name + ") (run " + std::to_string(run->run) + ") |";
      } catch (const std::exception& e) {
        spdlog::warn("bench {}: no HTML report {}: {}", r.input.name, name, e.what());
        row += " – |";
      }
    }
    rows += row + "\n";
  }
  if (rows.empty()) return {};
  return "\n## Run reports\n\nOne self-contained HTML report (`stillslam report`) per mode: its median run, with "
         "the other mode's median run overlaid.\n\n| sequence | segmentation off | segmentation on |\n|---|---|---|\n" +
         rows;
}

}  // namespace

ReportFiles write_benchmark_report(const std::filesystem::path& dir, const std::vector<SequenceResult>& results,
                                   const BenchmarkOptions& options) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error("cannot create the report folder " + dir.string() + ": " + ec.message());
  std::vector<SequencePlots> plots(results.size());
  for (std::size_t i = 0; i < results.size(); ++i) {
    if (results[i].error) continue;
    try {
      plots[i] = write_sequence_plots(dir, results[i]);
    } catch (const std::exception& e) {
      // A figure that cannot be drawn must not cost the numbers.
      spdlog::warn("bench {}: no plots: {}", results[i].input.name, e.what());
    }
  }
  ReportFiles files{dir / "report.md", dir / "results.json", {}};
  write_text_file(files.results, json_text(benchmark_to_json(results, options), 1) + "\n");
  std::string markdown = benchmark_markdown(results, options, plots);
  if (!options.output_dir.empty()) markdown += write_mode_reports(dir, results, files.run_reports);
  write_text_file(files.report, markdown);
  return files;
}

}  // namespace stillslam
