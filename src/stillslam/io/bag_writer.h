#pragma once
// Writes ROS 2 bags: sqlite3 (.db3, the rosbag2 Humble schema) or MCAP
// (chunks compressed with zstd, lz4 or none, or no chunks; with or without
// the summary section). A path ending in .db3 / .mcap is written as that
// bare file; any other path becomes a bag folder holding metadata.yaml and
// <folder name>_0.db3 / .mcap. close() finishes the files (also run by the
// destructor, which swallows errors: call close() to see them).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "stillslam/io/bag_metadata.h"

namespace stillslam {

struct BagWriterOptions {
  std::string format = "mcap";       // "mcap" or "db3"
  std::string compression = "zstd";  // MCAP chunks: "zstd", "lz4", "none"
  bool chunked = true;               // MCAP: messages in chunks (false: plain records)
  bool summary = true;               // MCAP: summary section (schemas, channels, statistics, chunk index)
  std::size_t chunk_size = 4 << 20;  // MCAP: uncompressed bytes per chunk before it is written
  void check() const;
};

class BagWriter {
 public:
  virtual ~BagWriter() = default;
  std::uint32_t add_topic(const std::string& name, const std::string& type);
  void write(std::uint32_t topic, std::int64_t log_time_ns, const std::vector<std::uint8_t>& cdr);
  void close();
  const std::filesystem::path& path() const { return path_; }

 protected:
  explicit BagWriter(std::filesystem::path path, std::filesystem::path folder)
      : path_(std::move(path)), folder_(std::move(folder)) {}
  virtual void on_topic(std::uint32_t topic, const BagTopic& t) = 0;
  virtual void on_message(std::uint32_t topic, std::int64_t log_time_ns, const std::vector<std::uint8_t>& cdr) = 0;
  virtual void on_close() = 0;
  virtual std::string storage() const = 0;

  std::filesystem::path path_;    // the storage file
  std::filesystem::path folder_;  // the bag folder (metadata.yaml), empty for a bare file
  std::vector<BagTopic> topics_;
  std::int64_t first_ns_ = 0, last_ns_ = 0;
  bool closed_ = false;
};

std::unique_ptr<BagWriter> open_bag_writer(const std::filesystem::path& path, const BagWriterOptions& options);

}  // namespace stillslam
