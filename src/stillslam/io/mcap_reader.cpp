#include "stillslam/io/mcap_reader.h"

#include <cstring>

#include "stillslam/core/byte_io.h"
#include "stillslam/core/error.h"
#include "stillslam/io/mcap_compression.h"
#include "stillslam/io/mcap_records.h"

namespace stillslam {
namespace {

// A parse failure inside one record; `offset` is the file offset it refers to.
struct Damage {
  std::uint64_t offset;
  std::string why;
};

ByteReader record_reader(const std::string& buffer, std::size_t begin, std::size_t size, std::uint64_t file_offset) {
  return ByteReader(buffer.data() + begin, size, [file_offset](const std::string& detail) {
    return Error("record at byte " + std::to_string(file_offset) + ": " + detail);
  });
}

}  // namespace

McapReader::McapReader(const std::filesystem::path& mcap) : BagReader(mcap) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(mcap, ec)) throw Error(mcap.string() + ": bag file not found");
  in_.open(mcap, std::ios::binary);
  if (!in_) throw Error(mcap.string() + ": cannot be opened for reading (permission?)");
  scan();
}

std::string McapReader::read_at(std::uint64_t offset, std::uint64_t size) const {
  std::string out(size, '\0');
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(offset));
  in_.read(out.data(), static_cast<std::streamsize>(size));
  if (static_cast<std::uint64_t>(in_.gcount()) != size) {
    throw Error(file_.string() + ": file ends at byte " + std::to_string(offset + in_.gcount()) + " inside " +
                std::to_string(size) + " bytes at byte " + std::to_string(offset) + " (truncated MCAP)");
  }
  return out;
}

void McapReader::scan() {
  const std::uint64_t file_size = std::filesystem::file_size(file_);
  if (file_size < mcap::kMagic.size() || read_at(0, mcap::kMagic.size()) != mcap::kMagic) {
    throw Error(file_.string() + ": not an MCAP file (the magic bytes 0x89 'MCAP0' are missing at byte 0)");
  }
  std::uint64_t pos = mcap::kMagic.size();
  std::optional<std::uint64_t> summary_start;
  while (true) {
    if (pos == file_size) {
      stop_at_damage("at byte " + std::to_string(pos) + ": file ends without a DataEnd / Footer record (truncated)");
      break;
    }
    if (file_size - pos < mcap::kRecordHeader) {
      stop_at_damage("at byte " + std::to_string(pos) + ": file ends inside a record header (truncated)");
      break;
    }
    const std::string head = read_at(pos, mcap::kRecordHeader);
    const auto opcode = static_cast<std::uint8_t>(head[0]);
    std::uint64_t length;
    std::memcpy(&length, head.data() + 1, 8);
    const std::uint64_t content = pos + mcap::kRecordHeader;
    if (length > file_size - content) {
      stop_at_damage("at byte " + std::to_string(pos) + ": record (opcode " + std::to_string(opcode) + ") of " +
                     std::to_string(length) + " bytes runs past the file end at byte " + std::to_string(file_size) +
                     " (truncated)");
      break;
    }
    if (opcode == mcap::kDataEnd) break;
    if (opcode == mcap::kFooter) {
      break;
    }
    try {
      if (opcode == mcap::kChunk) {
        const std::string fixed = read_at(content, std::min<std::uint64_t>(length, 4096));
        ByteReader r = record_reader(fixed, 0, fixed.size(), pos);
        r.get<std::uint64_t>();  // message start time
        r.get<std::uint64_t>();  // message end time
        Chunk chunk;
        chunk.uncompressed_size = r.get<std::uint64_t>();
        const auto crc = r.get<std::uint32_t>();  // 0: not computed
        chunk.compression = r.get_string();
        chunk.size = r.get<std::uint64_t>();
        chunk.data_offset = content + (fixed.size() - r.remaining());
        if (chunk.size > length - (chunk.data_offset - content)) r.fail("chunk records run past the record end");
        if (!mcap_compression_known(chunk.compression)) {
          r.fail("chunk compression '" + chunk.compression + "' is not supported (zstd, lz4 or none)");
        }
        const std::string compressed = read_at(chunk.data_offset, chunk.size);
        const std::string records = mcap_decompress(chunk.compression, compressed.data(), compressed.size(),
                                                    chunk.uncompressed_size,
                                                    "chunk at byte " + std::to_string(pos));
        if (crc != 0 && mcap_crc32(records) != crc) {
          r.fail("chunk records do not match their CRC-32 (corrupt data)");
        }
        chunks_.push_back(chunk);
        const std::size_t before = messages_.size();
        try {
          scan_records(records, 0, static_cast<std::int64_t>(chunks_.size() - 1));
        } catch (const Error&) {
          // Keep only whole chunks' messages.
          for (std::size_t k = before; k < messages_.size(); ++k) --topics_[messages_[k].topic].message_count;
          messages_.resize(before);
          locations_.resize(before);
          chunks_.pop_back();
          throw;
        }
      } else if (opcode == mcap::kSchema || opcode == mcap::kChannel || opcode == mcap::kMessage) {
        // Outside chunks: parse this one record as a one-record buffer.
        std::string record = head + read_at(content, opcode == mcap::kMessage ? std::min<std::uint64_t>(length, 22 + 16) : length);
        if (opcode == mcap::kMessage) {
          std::memcpy(record.data() + 1, &length, 8);  // the header keeps the full length
        }
        scan_records(record, pos, -1);
      }
    } catch (const Error& e) {
      stop_at_damage(e.what());
      break;
    }
    pos = content + length;
  }
  // The summary only when the file ends as the spec says (footer + magic).
  if (damage_.empty() && file_size >= mcap::kFooterRecord + mcap::kMagic.size()) {
    const std::uint64_t footer = file_size - mcap::kMagic.size() - mcap::kFooterRecord;
    const std::string tail = read_at(footer, mcap::kFooterRecord + mcap::kMagic.size());
    if (tail.substr(mcap::kFooterRecord) == mcap::kMagic && static_cast<std::uint8_t>(tail[0]) == mcap::kFooter) {
      std::uint64_t start;
      std::memcpy(&start, tail.data() + mcap::kRecordHeader, 8);
      if (start != 0 && start < footer) summary_start = start;
    }
  }
  if (summary_start) {
    try {
      read_summary(*summary_start, file_size);
    } catch (const Error&) {
      summary_counts_.reset();  // the messages were read; a bad summary only loses the statistics
    }
  }
  if (summary_counts_) {
    std::vector<BagTopic> expected;
    for (const auto& [name, n] : *summary_counts_) {
      BagTopic t;
      t.name = name;
      t.message_count = n;
      expected.push_back(t);
    }
    warn_on_count_mismatch(*this, expected, file_.string() + " (summary)");
  }
}

// Message records append a location (offset relative to `buffer` for chunks,
// to the file for records outside chunks: `base` is the record's file offset).
void McapReader::scan_records(const std::string& buffer, std::uint64_t base, std::int64_t chunk) {
  std::size_t pos = 0;
  while (pos < buffer.size()) {
    const std::string at = chunk < 0 ? "record at byte " + std::to_string(base)
                                     : "record at byte " + std::to_string(pos) + " of the chunk at data offset " +
                                           std::to_string(chunks_[static_cast<std::size_t>(chunk)].data_offset);
    if (buffer.size() - pos < mcap::kRecordHeader) throw Error(at + ": chunk ends inside a record header");
    const auto opcode = static_cast<std::uint8_t>(buffer[pos]);
    std::uint64_t length;
    std::memcpy(&length, buffer.data() + pos + 1, 8);
    const std::size_t content = pos + mcap::kRecordHeader;
    const std::size_t available = buffer.size() - content;
    if (chunk >= 0 && length > available) throw Error(at + ": record runs past the chunk end");
    ByteReader r(buffer.data() + content, std::min<std::uint64_t>(length, available),
                 [&at](const std::string& detail) { return Error(at + ": " + detail); });
    if (opcode == mcap::kSchema) {
      const auto id = r.get<std::uint16_t>();
      schema_names_[id] = r.get_string();
    } else if (opcode == mcap::kChannel) {
      const auto id = r.get<std::uint16_t>();
      const auto schema = r.get<std::uint16_t>();
      BagTopic topic;
      topic.name = r.get_string();
      topic.serialization = r.get_string();
      const auto it = schema_names_.find(schema);
      topic.type = it != schema_names_.end() ? it->second : std::string();
      if (!topic_of_channel_.count(id)) topic_of_channel_[id] = add_topic(std::move(topic));
    } else if (opcode == mcap::kMessage) {
      const auto channel = r.get<std::uint16_t>();
      r.get<std::uint32_t>();  // sequence
      const auto log_time = r.get<std::uint64_t>();
      r.get<std::uint64_t>();  // publish time
      const auto it = topic_of_channel_.find(channel);
      if (it == topic_of_channel_.end()) r.fail("message on channel " + std::to_string(channel) + " before its Channel record");
      constexpr std::uint64_t kFixed = 2 + 4 + 8 + 8;
      if (length < kFixed) r.fail("message record too short");
      Location loc;
      loc.chunk = chunk;
      loc.offset = (chunk < 0 ? base : 0) + content + kFixed;
      loc.size = length - kFixed;
      const std::size_t data_at = content + kFixed;
      if (data_at < buffer.size()) {
        std::memcpy(loc.prefix.data(), buffer.data() + data_at,
                    std::min<std::size_t>({loc.prefix.size(), loc.size, buffer.size() - data_at}));
      }
      locations_.push_back(loc);
      messages_.push_back({it->second, static_cast<std::int64_t>(log_time)});
      ++topics_[it->second].message_count;
    }
    pos = content + length;
  }
}

void McapReader::read_summary(std::uint64_t start, std::uint64_t file_size) {
  const std::uint64_t end = file_size - mcap::kMagic.size() - mcap::kFooterRecord;
  const std::string summary = read_at(start, end - start);
  std::size_t pos = 0;
  std::map<std::uint16_t, std::string> topic_of_channel;
  std::optional<std::map<std::uint16_t, std::uint64_t>> counts;
  while (pos + mcap::kRecordHeader <= summary.size()) {
    const auto opcode = static_cast<std::uint8_t>(summary[pos]);
    std::uint64_t length;
    std::memcpy(&length, summary.data() + pos + 1, 8);
    const std::size_t content = pos + mcap::kRecordHeader;
    if (length > summary.size() - content) throw Error("summary record past its end");
    ByteReader r = record_reader(summary, content, length, start + pos);
    if (opcode == mcap::kChannel) {
      const auto id = r.get<std::uint16_t>();
      r.get<std::uint16_t>();
      topic_of_channel[id] = r.get_string();
    } else if (opcode == mcap::kStatistics) {
      r.get<std::uint64_t>();  // message count
      r.get<std::uint16_t>();  // schema count
      r.get<std::uint32_t>();  // channel count
      r.get<std::uint32_t>();  // attachment count
      r.get<std::uint32_t>();  // metadata count
      r.get<std::uint32_t>();  // chunk count
      r.get<std::uint64_t>();  // start time
      r.get<std::uint64_t>();  // end time
      const auto bytes = r.get<std::uint32_t>();
      if (bytes > r.remaining()) r.fail("channel message counts past the record end");
      counts.emplace();
      for (std::uint32_t k = 0; k + 10 <= bytes; k += 10) {
        const auto channel = r.get<std::uint16_t>();
        (*counts)[channel] = r.get<std::uint64_t>();
      }
    }
    pos = content + length;
  }
  if (!counts) return;
  summary_counts_.emplace();
  for (const auto& [channel, n] : *counts) {
    const auto it = topic_of_channel.find(channel);
    (*summary_counts_)[it != topic_of_channel.end() ? it->second : "channel " + std::to_string(channel)] += n;
  }
}

std::shared_ptr<const std::string> McapReader::chunk_data(std::size_t chunk) const {
  if (cached_chunk_ == static_cast<std::int64_t>(chunk)) return cached_;
  const Chunk& c = chunks_[chunk];
  const std::string compressed = read_at(c.data_offset, c.size);
  cached_ = std::make_shared<const std::string>(
      mcap_decompress(c.compression, compressed.data(), compressed.size(), c.uncompressed_size,
                      file_.string() + ": chunk at data offset " + std::to_string(c.data_offset)));
  cached_chunk_ = static_cast<std::int64_t>(chunk);
  return cached_;
}

std::vector<std::uint8_t> McapReader::read_prefix(std::size_t i, std::size_t n) const {
  const Location& loc = locations_.at(i);
  const std::size_t kept = std::min<std::size_t>(loc.prefix.size(), loc.size);
  if (n > kept && loc.size > kept) return BagReader::read_prefix(i, n);
  return std::vector<std::uint8_t>(loc.prefix.begin(), loc.prefix.begin() + static_cast<long>(std::min(n, kept)));
}

std::vector<std::uint8_t> McapReader::read(std::size_t i) const {
  const Location& loc = locations_.at(i);
  const std::lock_guard lock(mutex_);
  if (loc.chunk < 0) {
    const std::string bytes = read_at(loc.offset, loc.size);
    return std::vector<std::uint8_t>(bytes.begin(), bytes.end());
  }
  const auto data = chunk_data(static_cast<std::size_t>(loc.chunk));
  const auto* p = reinterpret_cast<const std::uint8_t*>(data->data()) + loc.offset;
  return std::vector<std::uint8_t>(p, p + loc.size);
}

}  // namespace stillslam
