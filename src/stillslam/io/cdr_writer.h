#pragma once
// Writes ROS 2 message payloads in little-endian CDR (XCDR1) with the
// encapsulation header 0x00 0x01 0x00 0x00, fields aligned as CdrReader reads them.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace stillslam {

class CdrWriter {
 public:
  CdrWriter();
  void u8(std::uint8_t v) { bytes_.push_back(v); }
  void boolean(bool v) { u8(v ? 1 : 0); }
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void u32(std::uint32_t v);
  void u64(std::uint64_t v);
  void f64(double v);
  void string(const std::string& s);
  void bytes(const std::uint8_t* data, std::size_t n);
  void f64_sequence(const std::vector<double>& v);
  void f64_array(const double* v, std::size_t n);

  const std::vector<std::uint8_t>& data() const { return bytes_; }
  std::vector<std::uint8_t> take() { return std::move(bytes_); }

 private:
  void align(std::size_t n);
  void raw(const void* p, std::size_t n);
  std::vector<std::uint8_t> bytes_;
};

}  // namespace stillslam
