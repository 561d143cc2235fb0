#include "stillslam/benchmark/benchmark_input.h"

#include <fstream>
#include <map>
#include <sstream>

#include "stillslam/core/error.h"
#include "stillslam/io/input_file.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

fs::path relative_to(const fs::path& base, const std::string& text) {
  const fs::path p(text);
  if (p.is_absolute()) return p;
  const fs::path candidate = base / p;
  std::error_code ec;
  return fs::exists(candidate, ec) ? candidate : p;
}

bool non_empty_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec) && fs::file_size(p, ec) > 0;
}

// A trailing '/' gives an empty filename; take the parent's then.
std::string folder_name(const fs::path& folder) {
  fs::path p = folder.lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  std::string name = p.filename().string();
  if (name.empty() || name == ".") name = fs::absolute(p).lexically_normal().filename().string();
  return name.empty() ? "sequence" : name;
}

}  // namespace

std::vector<BenchmarkInput> read_benchmark_list(const fs::path& list_file) {
  std::ifstream in = open_input_file(list_file, "sequence list");
  const fs::path base = list_file.parent_path();
  std::vector<BenchmarkInput> inputs;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    std::vector<std::string> fields;
    for (std::string w; words >> w;) fields.push_back(w);
    if (fields.empty()) continue;
    if (fields.size() > 3) {
      throw Error(list_file.string() + " line " + std::to_string(line_number) +
                  ": expected `folder [config [groundtruth]]`, got " + std::to_string(fields.size()) + " fields");
    }
    BenchmarkInput input;
    input.folder = relative_to(base, fields[0]);
    if (fields.size() > 1) input.config = relative_to(base, fields[1]);
    if (fields.size() > 2) input.groundtruth = relative_to(base, fields[2]);
    inputs.push_back(std::move(input));
  }
  if (inputs.empty()) throw Error("the sequence list " + list_file.string() + " names no sequence");
  return inputs;
}

void name_benchmark_inputs(std::vector<BenchmarkInput>& inputs) {
  std::map<std::string, int> seen;
  for (BenchmarkInput& input : inputs) {
    std::string name = input.name.empty() ? folder_name(input.folder) : input.name;
    const int n = ++seen[name];
    if (n > 1) name += "_" + std::to_string(n);
    input.name = name;
  }
}

fs::path find_groundtruth(const fs::path& folder) {
  const fs::path candidates[] = {folder / "groundtruth.txt",
                                 folder / "mav0" / "state_groundtruth_estimate0" / "data.csv",
                                 folder / "state_groundtruth_estimate0" / "data.csv"};
  for (const fs::path& c : candidates) {
    if (non_empty_file(c)) return c;
  }
  if (fs::exists(folder / "times.txt")) {
    const fs::path kitti[] = {folder / "poses.txt",
                              folder.lexically_normal().parent_path().parent_path() / "poses" /
                                  (folder_name(folder) + ".txt")};
    for (const fs::path& c : kitti) {
      if (non_empty_file(c)) return c;
    }
  }
  return {};
}

BenchmarkInput resolve_benchmark_input(const BenchmarkInput& input, const fs::path& default_config) {
  BenchmarkInput out = input;
  std::error_code ec;
  if (!fs::is_directory(input.folder, ec)) {
    throw Error("sequence folder " + input.folder.string() + " does not exist: check the --sequence/--list path");
  }
  if (out.config.empty()) out.config = default_config;
  if (out.config.empty()) {
    out.config = input.folder / "settings.yaml";
    if (!fs::exists(out.config, ec)) {
      throw Error("no settings for " + input.folder.string() +
                  ": there is no settings.yaml in the folder; pass --config (e.g. config/tum_fr3.yaml for "
                  "TUM fr3 sequences) or give it after the folder in the --list file");
    }
  } else if (!fs::exists(out.config, ec)) {
    throw Error("settings file " + out.config.string() + " does not exist");
  }
  if (out.groundtruth.empty()) out.groundtruth = find_groundtruth(input.folder);
  if (out.groundtruth.empty()) {
    throw Error("no ground truth in " + input.folder.string() +
                " (looked for groundtruth.txt, mav0/state_groundtruth_estimate0/data.csv, KITTI poses): give "
                "the file as the third field of a --list line");
  }
  if (!fs::exists(out.groundtruth, ec)) throw Error("ground truth file " + out.groundtruth.string() + " does not exist");
  return out;
}

Trajectory load_groundtruth(const fs::path& file, const fs::path& folder) {
  const TrajectoryFormat format = detect_trajectory_format(file);
  if (format == TrajectoryFormat::Kitti && fs::exists(folder / "times.txt")) {
    return read_kitti_trajectory(file, folder / "times.txt");
  }
  Trajectory gt = read_trajectory(file, format);
  if (gt.empty()) throw Error("ground truth file " + file.string() + " holds no poses");
  return gt;
}

}  // namespace stillslam
