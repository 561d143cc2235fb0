#pragma once
// MCAP storage ("ros2" profile, CDR messages): Schema and Channel records in
// the data section, messages in chunks (zstd / lz4 / none) followed by their
// MessageIndex records, or as plain records; then DataEnd, the optional
// summary (schemas, channels, Statistics, ChunkIndex records) and the Footer.
// Chunks carry the CRC-32 of their records; the data-section and summary
// CRCs are written as 0 ("not computed", allowed by the spec). The
// schemas carry the ros2msg definitions of ros2_message_definitions.h.
#include <fstream>
#include <map>

#include "stillslam/io/bag_writer.h"

namespace stillslam {

class McapWriter : public BagWriter {
 public:
  McapWriter(const std::filesystem::path& mcap, const std::filesystem::path& folder, const BagWriterOptions& options);
  ~McapWriter() override;

 protected:
  void on_topic(std::uint32_t topic, const BagTopic& t) override;
  void on_message(std::uint32_t topic, std::int64_t log_time_ns, const std::vector<std::uint8_t>& cdr) override;
  void on_close() override;
  std::string storage() const override { return "mcap"; }

 private:
  void put_record(std::uint8_t opcode, const std::string& content);  // to the file
  void flush_chunk();

  BagWriterOptions options_;
  std::ofstream out_;
  std::uint64_t offset_ = 0;  // bytes written to the file
  std::string schema_records_, channel_records_;  // copies for the summary
  std::string chunk_;  // records of the open chunk
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;  // channel -> (time, offset)
  std::uint64_t chunk_start_ = 0, chunk_end_ = 0;
  std::string chunk_index_records_;
  std::uint32_t chunk_count_ = 0;
  std::uint64_t message_count_ = 0;
  std::map<std::uint16_t, std::uint64_t> channel_counts_;
  std::vector<std::uint32_t> sequence_;
};

}  // namespace stillslam
