#pragma once
// Constants of the MCAP file format (public specification, mcap.dev/spec):
// the magic at both ends and the record opcodes. A record is opcode (uint8),
// content length (uint64 LE), content; strings and byte arrays inside have a
// uint32 length prefix, maps a uint32 byte length.
#include <cstdint>
#include <string_view>

namespace stillslam::mcap {

inline constexpr std::string_view kMagic{"\x89MCAP0\r\n", 8};

enum Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

inline constexpr std::size_t kRecordHeader = 9;  // opcode + uint64 length
inline constexpr std::size_t kFooterRecord = kRecordHeader + 8 + 8 + 4;

}  // namespace stillslam::mcap
