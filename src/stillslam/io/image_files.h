#pragma once
// Image files by name, for the commands that take folders of images
// (`stillslam segment`, `stillslam vocab`).
#include <filesystem>
#include <vector>

namespace stillslam {

// .png .jpg .jpeg .bmp .pgm .tif .tiff, in any case.
bool is_image_file(const std::filesystem::path& file);

// The regular image files directly in `dir` (not its subfolders), sorted.
std::vector<std::filesystem::path> image_files_in(const std::filesystem::path& dir);

}  // namespace stillslam
