#pragma once
// Which sequences a benchmark runs, with which settings and ground truth.
#include <filesystem>
#include <string>
#include <vector>

#include "stillslam/io/trajectory.h"

namespace stillslam {

struct BenchmarkInput {
  std::string name;                    // label in the report (unique per benchmark)
  std::filesystem::path folder;        // dataset folder (TUM, EuRoC, KITTI layout)
  std::filesystem::path config;        // settings YAML; empty: <folder>/settings.yaml
  std::filesystem::path groundtruth;   // empty: found in the folder (find_groundtruth)
};

// A list file: one sequence per line, `folder [config [groundtruth]]`,
// whitespace separated, '#' starts a comment. Relative paths are taken
// relative to the list file's folder when they exist there, else as given.
// Error naming the file when it cannot be read or lists nothing.
std::vector<BenchmarkInput> read_benchmark_list(const std::filesystem::path& list_file);

// Gives every input a name: its folder's last component (KITTI
// sequences/00 -> "00"), made unique with _2, _3 ... in order.
void name_benchmark_inputs(std::vector<BenchmarkInput>& inputs);

// Fills config (explicit, else `default_config`, else <folder>/settings.yaml)
// and groundtruth; Error naming what is missing and how to pass it.
BenchmarkInput resolve_benchmark_input(const BenchmarkInput& input, const std::filesystem::path& default_config);

// Ground truth inside a dataset folder, first match:
//   <folder>/groundtruth.txt                                (TUM RGB-D)
//   <folder>/mav0/state_groundtruth_estimate0/data.csv      (EuRoC, when not empty)
//   <folder>/state_groundtruth_estimate0/data.csv
//   <folder>/poses.txt, <folder>/../../poses/<name>.txt     (KITTI, with <folder>/times.txt)
// Empty path when none exists.
std::filesystem::path find_groundtruth(const std::filesystem::path& folder);

// Reads ground truth; KITTI pose files (12 numbers per line) take their stamps
// from <folder>/times.txt when it exists.
Trajectory load_groundtruth(const std::filesystem::path& file, const std::filesystem::path& folder);

}  // namespace stillslam
