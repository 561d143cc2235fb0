#include "stillslam/io/yaml_reader.h"

#include <cmath>
#include <string_view>

#include <opencv2/core.hpp>
#include <spdlog/spdlog.h>

#include "stillslam/core/error.h"
#include "stillslam/io/input_file.h"

namespace stillslam {

namespace {

// Some published ORB-SLAM3 files (Stereo-Inertial/EuRoC.yaml, Tbc) miss the
// comma at the end of a matrix row; older OpenCV parsers accepted that, 4.x
// does not. Returns the text with such commas added (unchanged if none): a
// comma after a digit or '.' followed by blanks, one line break, blanks and a
// number. One pass, no std::regex (its recursion overflowed the stack on a
// long run of blanks).
std::string add_missing_row_commas(const std::string& text) {
  const auto numeric = [](char c) { return (c >= '0' && c <= '9') || c == '.'; };
  const auto blank = [](char c) { return c == ' ' || c == '\t'; };
  const std::size_t n = text.size();
  std::string out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    out += text[i];
    if (!numeric(text[i])) continue;
    std::size_t j = i + 1;
    while (j < n && blank(text[j])) ++j;
    if (j < n && text[j] == '\r') ++j;
    if (j >= n || text[j] != '\n') continue;
    ++j;
    while (j < n && blank(text[j])) ++j;
    if (j < n && (text[j] == '-' || text[j] == '+')) ++j;
    if (j < n && numeric(text[j])) out += ',';
  }
  return out;
}

// A line OpenCV 4.6's parser may loop forever on, as "LINE: what is wrong",
// or "" when the layout is that of a settings file: the top level is a map
// whose first key starts in the first column, and no line starts a top-level
// block sequence ('-' in column 0, other than a '---' marker). Found by
// fuzz_settings and fuzz_euroc_sensor ("%YAML:1.0\n----t\n-\n-",
// "%YAML:1.0\n a: l\n14e-\n\n"; tests/fuzz/known_hangs), so refused before
// the parser runs.
std::string layout_problem(const std::string& text) {
  bool first_key_seen = false;
  std::size_t line = 1;
  for (std::size_t start = 0; start < text.size(); ++line) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view row(text.data() + start, end - start);
    start = end + 1;
    if (!row.empty() && row.back() == '\r') row.remove_suffix(1);
    const std::size_t first = row.find_first_not_of(" \t");
    if (first == std::string_view::npos || row[first] == '#' || row[0] == '%') continue;
    const bool marker = row.substr(0, 3) == "---" && (row.size() == 3 || row[3] == ' ' || row[3] == '\t');
    if (marker) continue;
    if (row[0] == '-') {
      return std::to_string(line) + ": the top level is a sequence ('-' in the first column), not 'key: value' lines";
    }
    if (!first_key_seen && first > 0) {
      return std::to_string(line) + ": the first key is indented; top-level keys start in the first column";
    }
    first_key_seen = true;
  }
  return "";
}

}  // namespace

std::optional<double> node_number(const cv::FileNode& node) {
  if (node.isInt()) return static_cast<double>(static_cast<int>(node));
  if (node.isReal()) return static_cast<double>(node);
  return std::nullopt;
}

YamlReader::YamlReader(const std::filesystem::path& file) : file_(file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) {
    throw Error(file.string() + ": settings file not found (check the path given to --config)");
  }
  // Read here (folder, permission and BOM handled by input_file.h), parsed from memory.
  const std::string text = read_input_file(file, "settings file");
  if (const std::string problem = layout_problem(text); !problem.empty()) {
    throw Error(file.string() + ":" + problem + "; pass a settings or sensor.yaml file");
  }
  constexpr int kFromMemory = cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML;
  try {
    storage_.open(text, kFromMemory);
  } catch (const cv::Exception& e) {
    const std::string repaired = add_missing_row_commas(text);
    bool ok = false;
    if (repaired != text) {
      try {
        ok = storage_.open(repaired, kFromMemory);
      } catch (const std::exception&) {
        ok = false;
      }
    }
    if (!ok) {
      throw Error(file.string() + ": not a valid OpenCV YAML file (it must start with '%YAML:1.0'; " + e.err +
                  ")");
    }
    spdlog::warn("{}: a matrix row misses its trailing comma; read as if it were there", file.string());
  } catch (const std::exception& e) {
    // OpenCV's parser can also fail with a standard exception (a
    // std::length_error on some damaged files, found by fuzz_settings).
    throw Error(file.string() + ": not a valid OpenCV YAML file (it must start with '%YAML:1.0'; " + e.what() + ")");
  }
  if (!storage_.isOpened()) {
    throw Error(file.string() + ": cannot be read as OpenCV YAML (it must start with '%YAML:1.0')");
  }
  // Keys are looked up in the top-level map; OpenCV asserts on any other
  // top level (a sequence or a single value).
  const cv::FileNode root = storage_.root();
  if (!root.isNone() && !root.isMap()) {
    throw Error(file.string() + ": the top level is a " + (root.isSeq() ? "sequence" : "single value") +
                ", not 'key: value' lines; pass a settings or sensor.yaml file");
  }
}

bool YamlReader::has(const std::string& key) const { return !storage_[key].isNone(); }

std::vector<std::string> YamlReader::keys() const {
  std::vector<std::string> out;
  const cv::FileNode root = storage_.root();
  if (!root.isMap()) return out;
  for (auto it = root.begin(); it != root.end(); ++it) out.push_back((*it).name());
  return out;
}

void YamlReader::fail(const std::string& key, const std::string& message) const {
  throw Error(file_.string() + ": key '" + key + "' " + message);
}

std::optional<double> YamlReader::optional_number(const std::string& key) const {
  const cv::FileNode n = storage_[key];
  if (n.isNone()) return std::nullopt;
  const auto value = node_number(n);
  if (!value || !std::isfinite(*value)) fail(key, "must be a number");
  return value;
}

double YamlReader::number(const std::string& key) const {
  const auto value = optional_number(key);
  if (!value) fail(key, "is missing (required)");
  return *value;
}

std::optional<int> YamlReader::optional_integer(const std::string& key) const {
  const auto value = optional_number(key);
  if (!value) return std::nullopt;
  if (std::round(*value) != *value || std::abs(*value) > 2e9) fail(key, "must be an integer");
  return static_cast<int>(*value);
}

int YamlReader::integer(const std::string& key) const {
  const auto value = optional_integer(key);
  if (!value) fail(key, "is missing (required)");
  return *value;
}

std::optional<std::string> YamlReader::optional_string(const std::string& key) const {
  const cv::FileNode n = storage_[key];
  if (n.isNone()) return std::nullopt;
  if (!n.isString()) fail(key, "must be a string");
  return static_cast<std::string>(n);
}

std::optional<std::vector<double>> YamlReader::optional_numbers(const std::string& key) const {
  const cv::FileNode n = storage_[key];
  if (n.isNone()) return std::nullopt;
  if (!n.isSeq()) fail(key, "must be a sequence of numbers like [1.0, 2.0]");
  std::vector<double> out;
  for (auto it = n.begin(); it != n.end(); ++it) {
    const auto value = node_number(*it);
    if (!value) fail(key, "must contain only numbers");
    out.push_back(*value);
  }
  return out;
}

std::optional<Eigen::MatrixXd> YamlReader::optional_matrix(const std::string& key) const {
  const cv::FileNode n = storage_[key];
  if (n.isNone()) return std::nullopt;
  if (!n.isMap()) fail(key, "must be a matrix (rows, cols, data)");
  const auto rows = node_number(n["rows"]);
  const auto cols = node_number(n["cols"]);
  const cv::FileNode data = n["data"];
  if (!rows || !cols || *rows < 1 || *cols < 1 || !data.isSeq()) {
    fail(key, "must be a matrix with positive 'rows', 'cols' and a 'data' sequence");
  }
  // Whole numbers small enough that rows * cols cannot overflow.
  constexpr double kMaxSide = 1e6;
  if (*rows != std::floor(*rows) || *cols != std::floor(*cols) || *rows > kMaxSide || *cols > kMaxSide) {
    fail(key, "must have whole 'rows' and 'cols' up to 1000000");
  }
  const auto r = static_cast<int>(*rows);
  const auto c = static_cast<int>(*cols);
  if (data.size() != static_cast<std::size_t>(r) * static_cast<std::size_t>(c)) {
    fail(key, "has " + std::to_string(data.size()) + " data values but rows*cols = " +
                  std::to_string(static_cast<std::size_t>(r) * static_cast<std::size_t>(c)));
  }
  Eigen::MatrixXd m(r, c);
  int i = 0;
  for (auto it = data.begin(); it != data.end(); ++it, ++i) {
    const auto value = node_number(*it);
    if (!value) fail(key, "data must contain only numbers");
    m(i / c, i % c) = *value;  // row-major, as OpenCV writes it
  }
  return m;
}

}  // namespace stillslam
