#include "stillslam/io/dataset.h"

#include "stillslam/core/error.h"
#include "stillslam/io/bag_dataset.h"
#include "stillslam/io/bag_reader.h"
#include "stillslam/io/euroc_dataset.h"
#include "stillslam/io/kitti_dataset.h"
#include "stillslam/io/tum_dataset.h"

namespace stillslam {
namespace {

std::string settings_name(const CameraSettings& settings) {
  return settings.file.empty() ? std::string("the settings") : "the settings " + settings.file.string();
}

// A stereo folder read with RGB-D settings would run stereo with the RGB-D
// calibration's baseline (or none): the settings and the folder must agree.
void require_not_rgbd(const CameraSettings& settings, const std::filesystem::path& path, const std::string& layout) {
  if (!settings.rgbd) return;
  throw Error(path.string() + ": a " + layout + " stereo folder, but " + settings_name(settings) +
              " describe an RGB-D camera (RGBD.DepthMapFactor / DepthMapFactor given, no stereo pair): use stereo "
              "settings (Camera2.* with Stereo.T_c1_c2, or Camera.bf / Stereo.b without DepthMapFactor, as in "
              "config/euroc.yaml and config/kitti_*.yaml), or give a TUM RGB-D folder (rgb.txt, depth.txt)");
}

void require_not_stereo(const CameraSettings& settings, const std::filesystem::path& path) {
  if (!settings.stereo) return;
  throw Error(path.string() + ": a TUM RGB-D folder, but " + settings_name(settings) +
              " describe a stereo pair (Camera2.* / LEFT.* blocks, Camera.type \"Rectified\", or a baseline "
              "without DepthMapFactor): use RGB-D settings with RGBD.DepthMapFactor (as in config/tum_fr*.yaml), "
              "or give a stereo folder (EuRoC mav0/cam0 + cam1, KITTI image_0 + image_1)");
}

}  // namespace

std::unique_ptr<Dataset> open_dataset(const std::filesystem::path& path, const CameraSettings& settings,
                                      const DatasetOptions& options) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (is_bag_path(path)) return std::make_unique<BagDataset>(path, settings, options);
  // An association file given directly: a TUM sequence in its folder.
  if (fs::is_regular_file(path, ec)) {
    DatasetOptions with_file = options;
    with_file.association_file = path;
    require_not_stereo(settings, path);
    return std::make_unique<TumDataset>(path.parent_path(), settings, with_file);
  }
  if (!fs::is_directory(path, ec)) throw Error(path.string() + ": dataset folder not found");

  const auto is_file = [&](const fs::path& p) { return fs::is_regular_file(p, ec); };
  const bool tum = options.association_file || is_file(path / "associations.txt") ||
                   is_file(path / "associate.txt") || is_file(path / "rgb.txt");
  const bool euroc_root = is_file(path / "mav0" / "cam0" / "data.csv");
  const bool euroc_mav0 = is_file(path / "cam0" / "data.csv");
  // A folder can hold both an RGB-D (TUM) and a stereo (EuRoC) layout, as
  // `stillslam simulate` writes: the settings decide (a stereo description
  // means stereo, anything else RGB-D).
  if (tum && (!(euroc_root || euroc_mav0) || !settings.stereo)) {
    require_not_stereo(settings, path);
    return std::make_unique<TumDataset>(path, settings, options);
  }
  if (euroc_root || euroc_mav0) require_not_rgbd(settings, path, "EuRoC");
  if (euroc_root) return std::make_unique<EurocDataset>(path / "mav0", settings, options);
  if (euroc_mav0) return std::make_unique<EurocDataset>(path, settings, options);
  if (is_file(path / "times.txt") && fs::is_directory(path / "image_0", ec)) {
    require_not_rgbd(settings, path, "KITTI");
    return std::make_unique<KittiDataset>(path, settings, options);
  }
  throw Error(path.string() +
              ": no known dataset layout found. Looked for: TUM RGB-D (rgb.txt + depth.txt, or "
              "associations.txt / associate.txt), EuRoC (mav0/cam0/data.csv or cam0/data.csv), "
              "KITTI odometry (times.txt + image_0/), ROS 2 bag (metadata.yaml, or a .db3 / .mcap file)");
}

}  // namespace stillslam
