#include "stillslam/io/bag_reader.h"

#include <spdlog/spdlog.h>

#include "stillslam/core/error.h"
#include "stillslam/io/bag_file_set.h"
#include "stillslam/io/bag_metadata.h"
#include "stillslam/io/bag_sqlite_reader.h"
#include "stillslam/io/mcap_reader.h"

namespace stillslam {
namespace {

std::unique_ptr<BagReader> open_file(const std::filesystem::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".mcap") return std::make_unique<McapReader>(file);
  if (ext == ".db3") return std::make_unique<SqliteBagReader>(file);
  throw Error(file.string() + ": not a ROS 2 bag file (expected a .db3 or .mcap file; compressed .zstd bag files "
                              "are not supported: decompress them with `ros2 bag decompress` or zstd -d)");
}

}  // namespace

void BagReader::stop_at_damage(const std::string& detail) {
  damage_ = file_.string() + ": " + detail;
  if (messages_.empty()) throw Error(damage_ + " (no message could be read)");
  spdlog::warn("{}; the bag is damaged there: using the {} messages before it", damage_, messages_.size());
}

std::vector<std::uint8_t> BagReader::read_prefix(std::size_t i, std::size_t n) const {
  std::vector<std::uint8_t> bytes = read(i);
  if (bytes.size() > n) bytes.resize(n);
  return bytes;
}

std::uint32_t BagReader::add_topic(BagTopic topic) {
  topic.message_count = 0;
  topics_.push_back(std::move(topic));
  return static_cast<std::uint32_t>(topics_.size() - 1);
}

std::optional<std::uint32_t> BagReader::find_topic(const std::string& name) const {
  for (std::size_t i = 0; i < topics_.size(); ++i) {
    if (topics_[i].name == name) return static_cast<std::uint32_t>(i);
  }
  return std::nullopt;
}

std::string BagReader::topic_list() const {
  std::string out;
  for (const BagTopic& t : topics_) {
    out += (out.empty() ? "" : ", ") + t.name + " (" + t.type + ", " + std::to_string(t.message_count) + " messages)";
  }
  return out.empty() ? "no topics" : out;
}

bool is_bag_path(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(path, ec)) {
    const std::string ext = path.extension().string();
    return ext == ".mcap" || ext == ".db3";
  }
  return std::filesystem::is_regular_file(path / "metadata.yaml", ec);
}

std::unique_ptr<BagReader> open_bag(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(path, ec)) return open_file(path);
  if (!std::filesystem::is_directory(path, ec)) throw Error(path.string() + ": bag not found");
  const BagMetadata metadata = read_bag_metadata(path / "metadata.yaml");
  std::vector<std::unique_ptr<BagReader>> files;
  for (const std::string& f : metadata.relative_file_paths) files.push_back(open_file(path / f));
  std::unique_ptr<BagReader> bag =
      files.size() == 1 ? std::move(files.front()) : std::make_unique<BagFileSet>(path, std::move(files));
  warn_on_count_mismatch(*bag, metadata.topics, (path / "metadata.yaml").string());
  return bag;
}

void warn_on_count_mismatch(const BagReader& bag, const std::vector<BagTopic>& expected, const std::string& source) {
  for (const BagTopic& e : expected) {
    const auto t = bag.find_topic(e.name);
    const std::size_t got = t ? bag.topics()[*t].message_count : 0;
    if (got != e.message_count) {
      spdlog::warn("{} lists {} messages on {}, the bag holds {} (an interrupted recording or a damaged file?)",
                   source, e.message_count, e.name, got);
    }
  }
}

}  // namespace stillslam
