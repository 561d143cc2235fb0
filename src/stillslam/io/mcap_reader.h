#pragma once
// MCAP bags (ROS 2 Iron and later; public spec). Opening scans the data
// section record by record (chunks decompressed: zstd, lz4 or none), so a
// file without summary or index reads the same as an indexed one; a chunk
// whose CRC-32 is given and does not match is damage; the
// summary's Statistics, when present, is kept for checking the counts.
// read(i) reads message i from its chunk (the last decompressed chunk is
// cached) or from the file.
#include <array>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#include "stillslam/io/bag_reader.h"

namespace stillslam {

class McapReader : public BagReader {
 public:
  explicit McapReader(const std::filesystem::path& mcap);
  std::string storage() const override { return "mcap"; }
  std::vector<std::uint8_t> read(std::size_t i) const override;
  // The first 16 bytes of every message are kept from the scan (header
  // stamps without decompressing a chunk again).
  std::vector<std::uint8_t> read_prefix(std::size_t i, std::size_t n) const override;
  // Per-topic message counts of the summary's Statistics record (absent
  // without a summary).
  const std::optional<std::map<std::string, std::uint64_t>>& summary_counts() const { return summary_counts_; }
  std::size_t chunk_count() const { return chunks_.size(); }

 private:
  struct Chunk {
    std::uint64_t data_offset = 0;  // file offset of the compressed records
    std::uint64_t size = 0;
    std::uint64_t uncompressed_size = 0;
    std::string compression;
  };
  struct Location {
    std::int64_t chunk = -1;  // -1: a message record outside chunks
    std::uint64_t offset = 0;  // in the chunk's records, or in the file
    std::uint64_t size = 0;
    std::array<std::uint8_t, 16> prefix{};
  };
  void scan();
  // Records of one buffer (the data section's, or a chunk's); returns false at a Footer / DataEnd.
  void scan_records(const std::string& buffer, std::uint64_t base, std::int64_t chunk);
  void read_summary(std::uint64_t summary_start, std::uint64_t file_size);
  std::string read_at(std::uint64_t offset, std::uint64_t size) const;  // under mutex_
  std::shared_ptr<const std::string> chunk_data(std::size_t chunk) const;  // under mutex_

  std::vector<Chunk> chunks_;
  std::vector<Location> locations_;
  std::map<std::uint16_t, std::string> schema_names_;
  std::map<std::uint16_t, std::uint32_t> topic_of_channel_;
  std::optional<std::map<std::string, std::uint64_t>> summary_counts_;

  mutable std::mutex mutex_;
  mutable std::ifstream in_;
  mutable std::int64_t cached_chunk_ = -1;
  mutable std::shared_ptr<const std::string> cached_;
};

}  // namespace stillslam
