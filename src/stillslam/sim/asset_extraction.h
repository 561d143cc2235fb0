#pragma once
// Rebuilds data/textures and data/cutouts from a COCO128 YOLO-seg folder
// (images/<split>/<id>.jpg, labels/<split>/<id>.txt, class 1 = person).
//  - textures: photos with a label file and no person, ranked by how evenly
//    FAST corners cover them (ORB needs corners everywhere the camera looks);
//  - cut-outs: large, full-body person polygons that do not touch the image
//    border nor overlap another person, cropped as RGBA with alpha = polygon.
#include <filesystem>
#include <string>
#include <vector>

namespace stillslam::sim {

struct AssetExtractionOptions {
  int textures = 24;
  int cutouts = 12;
  int min_person_height = 110;   // pixels in the source photo
  double min_aspect = 1.4;       // bbox height / width: standing, whole body
  // Cut-outs to skip after visual inspection (e.g. "000000000257_0"), with the reason in the README.
  std::vector<std::string> exclude;
  // Seated people, written as sitting_<id>_<index>.png (used for people who stay still).
  std::vector<std::string> sitting;
};

struct ExtractedAssets {
  std::vector<std::string> texture_files, cutout_files;
};

ExtractedAssets extract_assets(const std::filesystem::path& coco_dir,
                               const std::filesystem::path& data_dir,
                               const AssetExtractionOptions& options);

}  // namespace stillslam::sim
