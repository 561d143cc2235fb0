#pragma once
// Line-based text lists used by the dataset formats (TUM rgb.txt,
// associations, EuRoC data.csv, KITTI times.txt/calib.txt): '#' comments and
// blank lines skipped, fields split on whitespace and/or commas.
#include <filesystem>
#include <string>
#include <vector>

namespace stillslam {

struct TextRow {
  std::size_t line = 0;  // 1-based line number in the file, for messages
  std::vector<std::string> fields;
};

// Throws Error when the file is missing, a folder or unreadable (io/input_file.h);
// a leading UTF-8 BOM is skipped.
std::vector<TextRow> read_text_table(const std::filesystem::path& file);

// Parses a field as a number; throws Error "<file>:<line>: ..." otherwise.
double parse_double(const std::string& field, const std::filesystem::path& file, std::size_t line);
long long parse_int64(const std::string& field, const std::filesystem::path& file, std::size_t line);

}  // namespace stillslam
