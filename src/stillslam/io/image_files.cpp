#include "stillslam/io/image_files.h"

#include <algorithm>
#include <string>

#include "stillslam/core/text.h"

namespace stillslam {

bool is_image_file(const std::filesystem::path& file) {
  const std::string ext = lower(file.extension().string());
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".pgm" || ext == ".tif" ||
         ext == ".tiff";
}

std::vector<std::filesystem::path> image_files_in(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.is_regular_file() && is_image_file(e.path())) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace stillslam
