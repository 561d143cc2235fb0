#include "stillslam/io/mcap_writer.h"

#include "stillslam/core/byte_io.h"
#include "stillslam/core/error.h"
#include "stillslam/io/mcap_compression.h"
#include "stillslam/io/mcap_records.h"
#include "stillslam/io/ros2_message_definitions.h"

namespace stillslam {
namespace {

std::string record(std::uint8_t opcode, const std::string& content) {
  ByteWriter w;
  w.put(opcode);
  w.put(static_cast<std::uint64_t>(content.size()));
  w.put_bytes(content.data(), content.size());
  return std::move(w.bytes());
}

}  // namespace

McapWriter::McapWriter(const std::filesystem::path& mcap, const std::filesystem::path& folder,
                       const BagWriterOptions& options)
    : BagWriter(mcap, folder), options_(options), out_(mcap, std::ios::binary | std::ios::trunc) {
  if (!out_) throw Error(mcap.string() + ": cannot be created (missing folder or no permission)");
  out_.write(mcap::kMagic.data(), mcap::kMagic.size());
  offset_ = mcap::kMagic.size();
  ByteWriter header;
  header.put_string("ros2");
  header.put_string("stillslam");
  put_record(mcap::kHeader, header.bytes());
}

McapWriter::~McapWriter() {
  try {
    close();
  } catch (const Error&) {
    // close() reports errors to callers that call it; a destructor must not throw.
  }
}

void McapWriter::put_record(std::uint8_t opcode, const std::string& content) {
  const std::string r = record(opcode, content);
  out_.write(r.data(), static_cast<std::streamsize>(r.size()));
  if (!out_) throw Error(path_.string() + ": write failed at byte " + std::to_string(offset_) + " (disk full?)");
  offset_ += r.size();
}

void McapWriter::on_topic(std::uint32_t topic, const BagTopic& t) {
  // Schema and channel ids are the topic index + 1 (schema id 0 means "no schema").
  const auto id = static_cast<std::uint16_t>(topic + 1);
  ByteWriter schema;
  schema.put(id);
  schema.put_string(t.type);
  schema.put_string("ros2msg");
  schema.put_string(ros2::message_definition(t.type));  // empty for other types
  ByteWriter channel;
  channel.put(id);
  channel.put(id);
  channel.put_string(t.name);
  channel.put_string("cdr");
  channel.put(static_cast<std::uint32_t>(0));  // metadata map: empty
  put_record(mcap::kSchema, schema.bytes());
  put_record(mcap::kChannel, channel.bytes());
  schema_records_ += record(mcap::kSchema, schema.bytes());
  channel_records_ += record(mcap::kChannel, channel.bytes());
  sequence_.push_back(0);
}

void McapWriter::on_message(std::uint32_t topic, std::int64_t log_time_ns, const std::vector<std::uint8_t>& cdr) {
  const auto channel = static_cast<std::uint16_t>(topic + 1);
  const auto time = static_cast<std::uint64_t>(log_time_ns);
  ByteWriter m;
  m.put(channel);
  m.put(sequence_[topic]++);
  m.put(time);
  m.put(time);
  m.put_bytes(cdr.data(), cdr.size());
  ++message_count_;
  ++channel_counts_[channel];
  if (!options_.chunked) {
    put_record(mcap::kMessage, m.bytes());
    return;
  }
  if (chunk_.empty()) chunk_start_ = chunk_end_ = time;
  chunk_start_ = std::min(chunk_start_, time);
  chunk_end_ = std::max(chunk_end_, time);
  chunk_index_[channel].emplace_back(time, chunk_.size());
  chunk_ += record(mcap::kMessage, m.bytes());
  if (chunk_.size() >= options_.chunk_size) flush_chunk();
}

void McapWriter::flush_chunk() {
  if (chunk_.empty()) return;
  const std::string compression = options_.compression == "none" ? "" : options_.compression;
  const std::string compressed = mcap_compress(compression, chunk_);
  ByteWriter c;
  c.put(chunk_start_);
  c.put(chunk_end_);
  c.put(static_cast<std::uint64_t>(chunk_.size()));
  c.put(mcap_crc32(chunk_));
  c.put_string(compression);
  c.put(static_cast<std::uint64_t>(compressed.size()));
  c.put_bytes(compressed.data(), compressed.size());
  const std::uint64_t chunk_offset = offset_;
  put_record(mcap::kChunk, c.bytes());
  const std::uint64_t chunk_length = offset_ - chunk_offset;
  // MessageIndex records, one per channel, and the ChunkIndex that points at them.
  ByteWriter offsets;
  const std::uint64_t index_start = offset_;
  for (const auto& [channel, entries] : chunk_index_) {
    ByteWriter mi;
    mi.put(channel);
    mi.put(static_cast<std::uint32_t>(entries.size() * 16));
    for (const auto& [time, at] : entries) {
      mi.put(time);
      mi.put(at);
    }
    offsets.put(channel);
    offsets.put(offset_);
    put_record(mcap::kMessageIndex, mi.bytes());
  }
  ByteWriter ci;
  ci.put(chunk_start_);
  ci.put(chunk_end_);
  ci.put(chunk_offset);
  ci.put(chunk_length);
  ci.put(static_cast<std::uint32_t>(offsets.bytes().size()));
  ci.put_bytes(offsets.bytes().data(), offsets.bytes().size());
  ci.put(offset_ - index_start);
  ci.put_string(compression);
  ci.put(static_cast<std::uint64_t>(compressed.size()));
  ci.put(static_cast<std::uint64_t>(chunk_.size()));
  chunk_index_records_ += record(mcap::kChunkIndex, ci.bytes());
  ++chunk_count_;
  chunk_.clear();
  chunk_index_.clear();
}

void McapWriter::on_close() {
  flush_chunk();
  put_record(mcap::kDataEnd, std::string(4, '\0'));
  std::uint64_t summary_start = 0;
  if (options_.summary) {
    summary_start = offset_;
    ByteWriter stats;
    stats.put(message_count_);
    stats.put(static_cast<std::uint16_t>(topics_.size()));
    stats.put(static_cast<std::uint32_t>(topics_.size()));
    stats.put(static_cast<std::uint32_t>(0));  // attachments
    stats.put(static_cast<std::uint32_t>(0));  // metadata
    stats.put(chunk_count_);
    stats.put(static_cast<std::uint64_t>(first_ns_));
    stats.put(static_cast<std::uint64_t>(last_ns_));
    stats.put(static_cast<std::uint32_t>(channel_counts_.size() * 10));
    for (const auto& [channel, n] : channel_counts_) {
      stats.put(channel);
      stats.put(n);
    }
    const std::string summary =
        schema_records_ + channel_records_ + record(mcap::kStatistics, stats.bytes()) + chunk_index_records_;
    out_.write(summary.data(), static_cast<std::streamsize>(summary.size()));
    offset_ += summary.size();
  }
  ByteWriter footer;
  footer.put(summary_start);
  footer.put(static_cast<std::uint64_t>(0));  // no summary offset section
  footer.put(static_cast<std::uint32_t>(0));  // CRC not computed
  put_record(mcap::kFooter, footer.bytes());
  out_.write(mcap::kMagic.data(), mcap::kMagic.size());
  out_.close();
  if (!out_) throw Error(path_.string() + ": write failed (disk full?)");
}

}  // namespace stillslam
