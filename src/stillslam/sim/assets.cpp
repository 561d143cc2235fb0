#include "stillslam/sim/assets.h"

#include <algorithm>
#include <cstdlib>
#include <opencv2/imgcodecs.hpp>

#include "stillslam/core/error.h"
#include "stillslam/core/text.h"

namespace stillslam::sim {
namespace fs = std::filesystem;
namespace {

bool is_data_dir(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p / "textures", ec) && fs::is_directory(p / "cutouts", ec);
}

std::vector<fs::path> files_with(const fs::path& dir, const std::vector<std::string>& exts) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const std::string ext = lower(e.path().extension().string());
    if (std::find(exts.begin(), exts.end(), ext) != exts.end()) out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

fs::path find_data_dir() {
  if (const char* env = std::getenv("STILLSLAM_DATA_DIR"); env && *env) {
    if (!is_data_dir(env)) {
      throw Error(std::string("STILLSLAM_DATA_DIR=") + env +
                  " has no textures/ and cutouts/ folders; point it at the repo's data/ folder");
    }
    return env;
  }
  std::vector<fs::path> starts;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) starts.push_back(exe.parent_path());
  starts.push_back(fs::current_path());
  for (fs::path p : starts) {
    for (; !p.empty(); p = p.parent_path()) {
      if (is_data_dir(p / "data")) return p / "data";
      if (p == p.root_path()) break;
    }
  }
  throw Error(
      "sim: cannot find the data/ folder with textures/ and cutouts/; set STILLSLAM_DATA_DIR to "
      "the repo's data/ folder or pass --data-dir");
}

AssetLibrary load_assets(const fs::path& data_dir) {
  if (!is_data_dir(data_dir)) {
    throw Error("sim: " + data_dir.string() +
                " must contain textures/ and cutouts/ (the repo's data/ folder)");
  }
  AssetLibrary lib;
  for (const auto& p : files_with(data_dir / "textures", {".jpg", ".jpeg", ".png"})) {
    cv::Mat img = cv::imread(p.string(), cv::IMREAD_COLOR);
    if (img.empty()) throw Error("sim: cannot read texture " + p.string());
    lib.textures.push_back(img);
    lib.texture_names.push_back(p.filename().string());
  }
  for (const auto& p : files_with(data_dir / "cutouts", {".png"})) {
    cv::Mat img = cv::imread(p.string(), cv::IMREAD_UNCHANGED);
    if (img.empty() || img.type() != CV_8UC4) {
      throw Error("sim: cut-out " + p.string() + " must be an 8-bit RGBA PNG");
    }
    const std::string name = p.filename().string();
    const bool seated = name.rfind("sitting_", 0) == 0;
    (seated ? lib.sitting : lib.cutouts).push_back(img);
    (seated ? lib.sitting_names : lib.cutout_names).push_back(name);
  }
  if (lib.textures.empty()) throw Error("sim: no textures in " + (data_dir / "textures").string());
  if (lib.cutouts.empty()) throw Error("sim: no cut-outs in " + (data_dir / "cutouts").string());
  return lib;
}

}  // namespace stillslam::sim
