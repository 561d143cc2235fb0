#include "stillslam/eval/evaluation_report.h"

#include <cstdio>
#include <fstream>

#include "stillslam/core/error.h"
#include "stillslam/core/json_text.h"
#include "stillslam/core/text_file.h"

namespace stillslam {

nlohmann::json to_json(const ErrorStatistics& stats) {
  if (stats.empty()) {  // absent, not zero
    return {{"rmse", nullptr}, {"mean", nullptr}, {"median", nullptr}, {"std", nullptr},
            {"min", nullptr},  {"max", nullptr},  {"count", 0}};
  }
  return {{"rmse", stats.rmse},     {"mean", stats.mean}, {"median", stats.median}, {"std", stats.std},
          {"min", stats.min},       {"max", stats.max},   {"count", stats.count}};
}

nlohmann::json evaluation_to_json(const EvaluationResult& result, const EvaluationOptions& options) {
  nlohmann::json rotation = nlohmann::json::array();
  for (int r = 0; r < 3; ++r) {
    rotation.push_back({result.alignment.rotation(r, 0), result.alignment.rotation(r, 1), result.alignment.rotation(r, 2)});
  }
  const Eigen::Vector3d& t = result.alignment.translation;
  return {
      {"pairs", result.pairs},
      {"gt_poses", result.gt_poses},
      {"est_poses", result.est_poses},
      {"ape", to_json(result.ape_stats)},
      {"rpe_trans", to_json(result.rpe_trans_stats)},
      {"rpe_rot", to_json(result.rpe_rot_stats)},
      {"rpe",
       {{"delta", options.rpe.delta},
        {"unit", to_string(options.rpe.unit)},
        {"all_pairs", options.rpe.all_pairs},
        {"pairs", result.rpe_pairs.size()}}},
      {"alignment",
       {{"type", to_string(result.alignment.type)},
        {"scale", result.alignment.scale},
        {"rotation", rotation},
        {"translation", {t.x(), t.y(), t.z()}}}},
      {"association",
       {{"method", to_string(options.association.method)},
        {"max_dt", options.association.effective_max_dt()},
        {"offset", options.association.offset}}},
  };
}

void write_evaluation_json(const std::filesystem::path& path, const EvaluationResult& result,
                           const EvaluationOptions& options, const nlohmann::json& extra) {
  nlohmann::json json = evaluation_to_json(result, options);
  for (const auto& [key, value] : extra.items()) json[key] = value;
  write_text_file(path, json_text(json, 2) + '\n');  // a non-UTF-8 input path must not throw
}

std::string format_evaluation_table(const EvaluationResult& result, const EvaluationOptions& options) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof(line), "associated %zu of %zu estimated / %zu ground-truth poses (%s, max dt %.3g s)\n",
                result.pairs, result.est_poses, result.gt_poses, to_string(options.association.method).c_str(),
                options.association.effective_max_dt());
  out += line;
  std::snprintf(line, sizeof(line), "alignment %s, scale %.6f; RPE over %zu pairs, delta %g %s%s\n",
                to_string(result.alignment.type).c_str(), result.alignment.scale, result.rpe_pairs.size(),
                options.rpe.delta, to_string(options.rpe.unit).c_str(), options.rpe.all_pairs ? " (all pairs)" : "");
  out += line;
  std::snprintf(line, sizeof(line), "%-16s %10s %10s %10s %10s %10s %10s\n", "metric", "rmse", "mean", "median", "std",
                "min", "max");
  out += line;
  auto row = [&](const char* name, const ErrorStatistics& s) {
    if (s.empty()) {
      std::snprintf(line, sizeof(line), "%-16s %10s %10s %10s %10s %10s %10s  (no pairs)\n", name, "n/a", "n/a", "n/a",
                    "n/a", "n/a", "n/a");
      out += line;
      return;
    }
    std::snprintf(line, sizeof(line), "%-16s %10.6f %10.6f %10.6f %10.6f %10.6f %10.6f\n", name, s.rmse, s.mean,
                  s.median, s.std, s.min, s.max);
    out += line;
  };
  row("ape [m]", result.ape_stats);
  row("rpe_trans [m]", result.rpe_trans_stats);
  row("rpe_rot [deg]", result.rpe_rot_stats);
  return out;
}

}  // namespace stillslam
