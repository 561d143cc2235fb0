#include "stillslam/io/bag_writer.h"

#include "stillslam/core/error.h"
#include "stillslam/io/bag_sqlite_writer.h"
#include "stillslam/io/mcap_compression.h"
#include "stillslam/io/mcap_writer.h"

namespace stillslam {

void BagWriterOptions::check() const {
  if (format != "mcap" && format != "db3") throw Error("bag format '" + format + "': use mcap or db3");
  if (compression != "zstd" && compression != "lz4" && compression != "none") {
    throw Error("bag compression '" + compression + "': use zstd, lz4 or none");
  }
  if (chunk_size == 0) throw Error("bag chunk size must be > 0 bytes");
}

std::uint32_t BagWriter::add_topic(const std::string& name, const std::string& type) {
  BagTopic t;
  t.name = name;
  t.type = type;
  topics_.push_back(t);
  const auto id = static_cast<std::uint32_t>(topics_.size() - 1);
  on_topic(id, t);
  return id;
}

void BagWriter::write(std::uint32_t topic, std::int64_t log_time_ns, const std::vector<std::uint8_t>& cdr) {
  if (topic >= topics_.size()) throw Error(path_.string() + ": write to unknown topic " + std::to_string(topic));
  if (closed_) throw Error(path_.string() + ": write after close");
  const bool first = first_ns_ == 0 && last_ns_ == 0;
  if (first || log_time_ns < first_ns_) first_ns_ = log_time_ns;
  if (first || log_time_ns > last_ns_) last_ns_ = log_time_ns;
  ++topics_[topic].message_count;
  on_message(topic, log_time_ns, cdr);
}

void BagWriter::close() {
  if (closed_) return;
  closed_ = true;
  on_close();
  if (folder_.empty()) return;
  BagMetadata m;
  m.storage_identifier = storage();
  m.relative_file_paths = {path_.filename().string()};
  m.topics = topics_;
  m.starting_time_ns = first_ns_;
  m.duration_ns = last_ns_ - first_ns_;
  write_bag_metadata(folder_ / "metadata.yaml", m);
}

std::unique_ptr<BagWriter> open_bag_writer(const std::filesystem::path& path, const BagWriterOptions& options) {
  options.check();
  const std::string ext = path.extension().string();
  std::filesystem::path file = path, folder;
  std::string format = options.format;
  if (ext == ".mcap" || ext == ".db3") {
    format = ext.substr(1);
  } else {
    folder = path;
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec) throw Error(folder.string() + ": cannot create the bag folder (" + ec.message() + ")");
    file = folder / (folder.filename().string() + "_0." + format);
  }
  std::error_code ec;
  if (std::filesystem::exists(file, ec)) {
    throw Error(file.string() + ": exists already; remove it or choose another output");
  }
  if (format == "db3") return std::make_unique<SqliteBagWriter>(file, folder);
  return std::make_unique<McapWriter>(file, folder, options);
}

}  // namespace stillslam
