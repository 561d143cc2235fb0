#include "stillslam/io/cdr_writer.h"

#include <bit>
#include <cstring>

namespace stillslam {

static_assert(std::endian::native == std::endian::little, "CdrWriter writes the host's little-endian layout");

CdrWriter::CdrWriter() : bytes_{0x00, 0x01, 0x00, 0x00} {}

void CdrWriter::align(std::size_t n) {
  const std::size_t pos = bytes_.size() - 4;  // alignment counts from the end of the header
  bytes_.resize(bytes_.size() + (n - pos % n) % n, 0);
}

void CdrWriter::raw(const void* p, std::size_t n) {
  const auto* b = static_cast<const std::uint8_t*>(p);
  bytes_.insert(bytes_.end(), b, b + n);
}

void CdrWriter::u32(std::uint32_t v) {
  align(4);
  raw(&v, 4);
}

void CdrWriter::u64(std::uint64_t v) {
  align(8);
  raw(&v, 8);
}

void CdrWriter::f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }

void CdrWriter::string(const std::string& s) {
  u32(static_cast<std::uint32_t>(s.size() + 1));
  raw(s.data(), s.size());
  u8(0);
}

void CdrWriter::bytes(const std::uint8_t* data, std::size_t n) {
  u32(static_cast<std::uint32_t>(n));
  if (n > 0) raw(data, n);
}

void CdrWriter::f64_sequence(const std::vector<double>& v) {
  u32(static_cast<std::uint32_t>(v.size()));
  f64_array(v.data(), v.size());
}

void CdrWriter::f64_array(const double* v, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) f64(v[i]);
}

}  // namespace stillslam
