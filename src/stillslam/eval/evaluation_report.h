#pragma once
// Machine- and human-readable summaries of an EvaluationResult.
#include <nlohmann/json.hpp>
#include <filesystem>
#include <string>

#include "stillslam/eval/evaluate.h"

namespace stillslam {

nlohmann::json to_json(const ErrorStatistics& stats);

// Keys: pairs, gt_poses, est_poses, ape{rmse,mean,median,std,min,max,count},
// rpe_trans{...} (m), rpe_rot{...} (deg) (values null and count 0 without pairs), rpe{delta,unit,all_pairs,pairs},
// alignment{type,scale,rotation (row-major 3x3),translation},
// association{method,max_dt,offset}.
nlohmann::json evaluation_to_json(const EvaluationResult& result, const EvaluationOptions& options);

// Writes evaluation_to_json (plus `extra` keys merged at the top level, e.g.
// "inputs") to `path`, pretty-printed, whole or not at all (core/atomic_file.h).
// Error naming the file and the cause when it cannot be written.
void write_evaluation_json(const std::filesystem::path& path, const EvaluationResult& result,
                           const EvaluationOptions& options, const nlohmann::json& extra = nlohmann::json::object());

// A fixed-width table of the statistics, for the terminal.
std::string format_evaluation_table(const EvaluationResult& result, const EvaluationOptions& options);

}  // namespace stillslam
