#include "stillslam/io/dataset.h"

#include "stillslam/core/error.h"
#include "stillslam/io/euroc_dataset.h"
#include "stillslam/io/kitti_dataset.h"
#include "stillslam/io/tum_dataset.h"

namespace stillslam {

std::unique_ptr<Dataset> open_dataset(const std::filesystem::path& path, const CameraSettings& settings,
                                      const DatasetOptions& options) {
  namespace fs = std::filesystem;
  std::error_code ec;
  // An association file given directly: a TUM sequence in its folder.
  if (fs::is_regular_file(path, ec)) {
    DatasetOptions with_file = options;
    with_file.association_file = path;
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
    return std::make_unique<TumDataset>(path, settings, options);
  }
  if (euroc_root) return std::make_unique<EurocDataset>(path / "mav0", settings, options);
  if (euroc_mav0) return std::make_unique<EurocDataset>(path, settings, options);
  if (is_file(path / "times.txt") && fs::is_directory(path / "image_0", ec)) {
    return std::make_unique<KittiDataset>(path, settings, options);
  }
  throw Error(path.string() +
              ": no known dataset layout found. Looked for: TUM RGB-D (rgb.txt + depth.txt, or "
              "associations.txt / associate.txt), EuRoC (mav0/cam0/data.csv or cam0/data.csv), "
              "KITTI odometry (times.txt + image_0/)");
}

}  // namespace stillslam
