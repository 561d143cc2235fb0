#pragma once
// Photo textures (data/textures) and person cut-outs (data/cutouts) the
// simulator builds scenes from. Both come from COCO photos; see the README in
// each folder for the source image ids and licenses.
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace stillslam::sim {

struct AssetLibrary {
  std::vector<cv::Mat> textures;  // CV_8UC3 photos without people, sorted by file name
  std::vector<cv::Mat> cutouts;   // CV_8UC4 people; alpha = COCO polygon, cropped to the person
  std::vector<cv::Mat> sitting;   // CV_8UC4 seated people (cutouts/sitting_*.png)
  std::vector<std::string> texture_names, cutout_names, sitting_names;
};

// The repo's data/ folder: $STILLSLAM_DATA_DIR, else the first data/ with
// textures/ and cutouts/ found walking up from the executable, else from the
// working directory. Throws stillslam::Error naming the variable to set.
std::filesystem::path find_data_dir();

// Loads data_dir/textures/*.{jpg,png} and data_dir/cutouts/*.png (sitting_*.png apart).
AssetLibrary load_assets(const std::filesystem::path& data_dir);

}  // namespace stillslam::sim
