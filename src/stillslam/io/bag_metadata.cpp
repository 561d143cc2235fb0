#include "stillslam/io/bag_metadata.h"

#include <fstream>
#include <sstream>

#include "stillslam/core/error.h"
#include "stillslam/io/input_file.h"

namespace stillslam {
namespace {

std::string trim_copy(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  std::string v = s.substr(b, e - b + 1);
  if (v.size() >= 2 && (v.front() == '\'' || v.front() == '"') && v.back() == v.front()) v = v.substr(1, v.size() - 2);
  return v;
}

std::size_t indent_of(const std::string& line) { return line.find_first_not_of(' '); }

// "key: value" -> value when `line` (after '- ' and blanks) starts with `key:`.
bool value_of(const std::string& line, const std::string& key, std::string& value) {
  std::string t = trim_copy(line);
  if (t.rfind("- ", 0) == 0) t = trim_copy(t.substr(2));
  if (t.rfind(key + ":", 0) != 0) return false;
  value = trim_copy(t.substr(key.size() + 1));
  return true;
}

}  // namespace

std::size_t BagMetadata::message_count() const {
  std::size_t n = 0;
  for (const BagTopic& t : topics) n += t.message_count;
  return n;
}

BagMetadata read_bag_metadata(const std::filesystem::path& file) {
  std::istringstream in(read_input_file(file, "rosbag2 metadata.yaml"));
  BagMetadata m;
  std::string line, value;
  enum class Section { None, Files, Topics } section = Section::None;
  std::size_t item_indent = std::string::npos;
  while (std::getline(in, line)) {
    if (trim_copy(line).empty()) continue;
    const std::size_t indent = indent_of(line);
    const bool item = line.compare(indent, 2, "- ") == 0;
    if (indent <= 2 && !item) {  // a key of rosbag2_bagfile_information
      section = Section::None;
      item_indent = std::string::npos;
      if (value_of(line, "storage_identifier", value)) m.storage_identifier = value;
      else if (line.find("relative_file_paths:") != std::string::npos) section = Section::Files;
      else if (line.find("topics_with_message_count:") != std::string::npos) section = Section::Topics;
      else if (indent == 2 && line.find("starting_time:") != std::string::npos) {
        std::string ns;
        if (std::getline(in, ns) && value_of(ns, "nanoseconds_since_epoch", value)) m.starting_time_ns = std::stoll(value);
      } else if (indent == 2 && line.find("duration:") != std::string::npos) {
        std::string ns;
        if (std::getline(in, ns) && value_of(ns, "nanoseconds", value)) m.duration_ns = std::stoll(value);
      }
      continue;
    }
    if (section == Section::Files && item) {
      m.relative_file_paths.push_back(trim_copy(line.substr(indent + 2)));
    } else if (section == Section::Topics) {
      if (item && (item_indent == std::string::npos || indent == item_indent)) {
        item_indent = indent;
        m.topics.emplace_back();
      }
      if (m.topics.empty()) continue;
      BagTopic& t = m.topics.back();
      if (value_of(line, "message_count", value)) t.message_count = std::stoull(value);
      else if (value_of(line, "name", value)) t.name = value;
      else if (value_of(line, "type", value)) t.type = value;
      else if (value_of(line, "serialization_format", value)) t.serialization = value;
    }
  }
  if (m.relative_file_paths.empty()) {
    throw Error(file.string() + ": lists no bag file (relative_file_paths is missing or empty); is this a rosbag2 "
                                "metadata.yaml?");
  }
  return m;
}

void write_bag_metadata(const std::filesystem::path& file, const BagMetadata& m) {
  std::ostringstream out;
  out << "rosbag2_bagfile_information:\n"
      << "  version: 5\n"
      << "  storage_identifier: " << m.storage_identifier << "\n"
      << "  duration:\n    nanoseconds: " << m.duration_ns << "\n"
      << "  starting_time:\n    nanoseconds_since_epoch: " << m.starting_time_ns << "\n"
      << "  message_count: " << m.message_count() << "\n"
      << "  topics_with_message_count:\n";
  for (const BagTopic& t : m.topics) {
    out << "    - topic_metadata:\n"
        << "        name: " << t.name << "\n"
        << "        type: " << t.type << "\n"
        << "        serialization_format: " << t.serialization << "\n"
        << "        offered_qos_profiles: ''\n"
        << "      message_count: " << t.message_count << "\n";
  }
  out << "  compression_format: ''\n  compression_mode: ''\n  relative_file_paths:\n";
  for (const std::string& f : m.relative_file_paths) out << "    - " << f << "\n";
  out << "  files:\n";
  for (const std::string& f : m.relative_file_paths) {
    out << "    - path: " << f << "\n      starting_time:\n        nanoseconds_since_epoch: " << m.starting_time_ns
        << "\n      duration:\n        nanoseconds: " << m.duration_ns << "\n      message_count: "
        << m.message_count() << "\n";
  }
  std::ofstream f(file, std::ios::binary | std::ios::trunc);
  f << out.str();
  if (!f) throw Error(file.string() + ": cannot write the bag's metadata.yaml (disk full or no permission?)");
}

}  // namespace stillslam
