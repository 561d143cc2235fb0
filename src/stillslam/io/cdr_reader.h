#pragma once
// Reads ROS 2 message payloads in CDR (XCDR1): a 4-byte encapsulation header
// (0x00 0x00 big endian, 0x00 0x01 little endian), then fields aligned to
// their size (at most 8) counted from the end of the header. Every read is
// bounds checked; a short or corrupt payload throws Error naming `what` (the
// topic and message) and the byte offset.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace stillslam {

class CdrReader {
 public:
  CdrReader(const std::uint8_t* data, std::size_t size, std::string what);

  std::uint8_t u8() { return take(1)[0]; }
  bool boolean() { return u8() != 0; }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  std::uint32_t u32();
  std::uint64_t u64();
  double f64();
  float f32();
  std::string string();
  // A sequence length that must fit in the rest of the payload at
  // `min_item_bytes` per item (a corrupt count fails here, not in an allocation).
  std::size_t sequence_length(std::size_t min_item_bytes);
  // A byte sequence (uint8[]): the pointer into the payload and its length.
  const std::uint8_t* bytes(std::size_t& n);
  std::vector<double> f64_sequence();
  void f64_array(double* out, std::size_t n);

  bool little_endian() const { return little_; }
  std::size_t offset() const { return pos_; }
  [[noreturn]] void fail(const std::string& detail) const;

 private:
  const std::uint8_t* take(std::size_t n);
  void align(std::size_t n);
  std::uint64_t swap_if_needed(std::uint64_t v, std::size_t n) const;

  const std::uint8_t* body_;
  std::size_t size_ = 0;
  std::size_t pos_ = 0;
  bool little_ = true;
  std::string what_;
};

}  // namespace stillslam
