#include "run_outputs.h"

#include <algorithm>

#include "stillslam/core/atomic_file.h"
#include "stillslam/core/error.h"
#include "stillslam/core/json_text.h"
#include "stillslam/io/trajectory.h"

namespace stillslam::apps {

namespace fs = std::filesystem;

namespace {

bool is_run_output(const std::string& name) {
  if (name == "stats.json" || name == "keyframes.txt") return true;
  return name.size() >= 14 && name.rfind("trajectory", 0) == 0 && name.substr(name.size() - 4) == ".txt";
}

std::string trajectory_with_map_ids(const RunResult& result) {
  std::string text = "# t x y z qx qy qz qw map_id (each pose in its map's frame)\n";
  for (std::size_t i = 0; i < result.trajectory.size(); ++i) {
    text += format_trajectory_line(result.trajectory[i], TrajectoryFormat::Tum) + ' ' +
            std::to_string(result.trajectory_map_ids[i]) + '\n';
  }
  return text;
}

}  // namespace

std::vector<fs::path> previous_run_files(const fs::path& dir) {
  std::error_code ec;
  const fs::file_status status = fs::status(dir, ec);
  if (!fs::exists(status)) return {};
  if (!fs::is_directory(status)) {
    throw Error("output " + dir.string() + " is not a folder; give a folder for --output");
  }
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    if (!entry.is_directory() && is_run_output(entry.path().filename().string())) files.push_back(entry.path());
  }
  if (ec) throw Error("cannot list output folder " + dir.string() + ": " + ec.message());
  std::sort(files.begin(), files.end());
  return files;
}

void prepare_output_folder(const fs::path& dir, const std::vector<fs::path>& files) {
  std::error_code ec;
  for (const fs::path& file : files) {
    if (!fs::remove(file, ec) && ec) {
      throw Error("cannot remove " + file.string() + " of the previous run: " + ec.message());
    }
  }
  fs::create_directories(dir, ec);
  if (ec) throw Error("cannot create output folder " + dir.string() + ": " + ec.message());
}

void check_map_path(const fs::path& path, const fs::path& output_dir) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    throw Error("--save-map " + path.string() + " is a folder; give the map file's path, e.g. " +
                (path / "map.bin").string());
  }
  const fs::path folder = path.parent_path();
  if (folder.empty() || fs::is_directory(folder, ec)) return;
  if (fs::weakly_canonical(folder, ec) == fs::weakly_canonical(output_dir, ec)) return;
  throw Error("--save-map " + path.string() + ": folder " + folder.string() + " does not exist; create it first");
}

std::vector<std::string> write_run_outputs(const fs::path& dir, const RunResult& result, nlohmann::json& stats) {
  std::vector<std::string> errors;
  auto attempt = [&errors](auto&& write) {
    try {
      write();
    } catch (const Error& e) {
      errors.push_back(e.what());
    }
  };
  attempt([&] { write_trajectory(dir / "trajectory.txt", result.trajectory); });
  attempt([&] { write_trajectory(dir / "keyframes.txt", result.keyframes); });
  attempt([&] { write_file_atomically(dir / "trajectory_maps.txt", trajectory_with_map_ids(result)); });
  if (!errors.empty()) stats["output_errors"] = errors;
  attempt([&] { write_file_atomically(dir / "stats.json", json_text(stats, 1) + "\n"); });
  return errors;
}

}  // namespace stillslam::apps
