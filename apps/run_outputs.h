#pragma once
// The output folder of `stillslam run` and the files written into it at the
// end. Every file is written whole or not at all (core/atomic_file.h); a file
// that cannot be written does not stop the others.
#include <filesystem>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include "stillslam/system/dataset_runner.h"

namespace stillslam::apps {

// The files of an earlier run in `dir` (trajectory*.txt, keyframes.txt,
// stats.json); none when `dir` does not exist. Error when `dir` is not a folder.
std::vector<std::filesystem::path> previous_run_files(const std::filesystem::path& dir);

// Removes exactly `files` (what previous_run_files found) and creates `dir`.
void prepare_output_folder(const std::filesystem::path& dir, const std::vector<std::filesystem::path>& files);

// Error unless `path` can take a map file: not a folder, and its folder exists
// (or is `output_dir`, created before the run).
void check_map_path(const std::filesystem::path& path, const std::filesystem::path& output_dir);

// Writes trajectory.txt, keyframes.txt, trajectory_maps.txt and stats.json.
// Each file that cannot be written gives one message naming it and the cause;
// the files that could be written are kept. `stats` gets the messages of the
// files written before it under "output_errors".
std::vector<std::string> write_run_outputs(const std::filesystem::path& dir, const RunResult& result,
                                           nlohmann::json& stats);

}  // namespace stillslam::apps
