#include "stillslam/io/text_table.h"

#include <cerrno>
#include <cstdlib>

#include "stillslam/core/error.h"
#include "stillslam/core/text.h"
#include "stillslam/io/input_file.h"

namespace stillslam {

std::vector<TextRow> read_text_table(const std::filesystem::path& file) {
  std::ifstream in = open_input_file(file, "file");
  std::vector<TextRow> rows;
  std::string line;
  std::size_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    TextRow row;
    row.line = number;
    row.fields = split_tokens(line, true);
    // A comment line starts with '#'; a '#' later on is part of a field.
    if (!row.fields.empty() && row.fields.front().front() != '#') rows.push_back(std::move(row));
  }
  return rows;
}

double parse_double(const std::string& field, const std::filesystem::path& file, std::size_t line) {
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(field.c_str(), &end);
  if (field.empty() || end != field.c_str() + field.size() || errno == ERANGE) {
    throw Error(file.string() + ":" + std::to_string(line) + ": expected a number, got '" + field + "'");
  }
  return value;
}

long long parse_int64(const std::string& field, const std::filesystem::path& file, std::size_t line) {
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(field.c_str(), &end, 10);
  if (field.empty() || end != field.c_str() + field.size() || errno == ERANGE) {
    throw Error(file.string() + ":" + std::to_string(line) + ": expected an integer, got '" + field + "'");
  }
  return value;
}

}  // namespace stillslam
