#pragma once
// Opening the text files stillslam reads (trajectories, lists, csv, YAML):
// one place for the messages when the path is missing, a folder or unreadable,
// and for skipping a UTF-8 byte order mark that some editors write first.
#include <filesystem>
#include <fstream>
#include <string>

namespace stillslam {

// Opens `path` for reading, positioned after a leading UTF-8 BOM if there is
// one. `what` names the file in messages ("trajectory file", "image list").
// Error "<what> <path> does not exist", "... is a folder, expected a file" or
// "... cannot be read: <reason>" otherwise.
std::ifstream open_input_file(const std::filesystem::path& path, const std::string& what);

// The whole file as text without a leading BOM; the same errors.
std::string read_input_file(const std::filesystem::path& path, const std::string& what);

}  // namespace stillslam
