#include "stillslam/benchmark/report.h"

#include <spdlog/spdlog.h>

#include <fstream>

#include "stillslam/core/error.h"
#include "stillslam/core/json_text.h"
#include "stillslam/core/text_file.h"

namespace stillslam {

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
  ReportFiles files{dir / "report.md", dir / "results.json"};
  write_text_file(files.results, json_text(benchmark_to_json(results, options), 1) + "\n");
  write_text_file(files.report, benchmark_markdown(results, options, plots));
  return files;
}

}  // namespace stillslam
