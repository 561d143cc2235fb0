#include "stillslam/io/cdr_reader.h"

#include <bit>
#include <cstring>

#include "stillslam/core/error.h"

namespace stillslam {

CdrReader::CdrReader(const std::uint8_t* data, std::size_t size, std::string what) : what_(std::move(what)) {
  if (size < 4) throw Error(what_ + ": CDR payload of " + std::to_string(size) + " bytes has no encapsulation header");
  if (data[0] != 0 || data[1] > 1) {
    throw Error(what_ + ": CDR encapsulation " + std::to_string(data[0]) + "," + std::to_string(data[1]) +
                " is not plain CDR (0,0 big endian or 0,1 little endian); XCDR2 / PL_CDR are not supported");
  }
  little_ = data[1] == 1;
  body_ = data + 4;
  size_ = size - 4;
}

void CdrReader::fail(const std::string& detail) const {
  throw Error(what_ + ": bad CDR at byte " + std::to_string(pos_ + 4) + ": " + detail);
}

void CdrReader::align(std::size_t n) {
  const std::size_t pad = (n - pos_ % n) % n;
  if (pad > size_ - pos_) fail("payload ends inside padding");
  pos_ += pad;
}

const std::uint8_t* CdrReader::take(std::size_t n) {
  if (n > size_ - pos_) fail("payload ends (" + std::to_string(size_ - pos_) + " bytes left, " + std::to_string(n) + " needed)");
  const std::uint8_t* p = body_ + pos_;
  pos_ += n;
  return p;
}

std::uint64_t CdrReader::swap_if_needed(std::uint64_t v, std::size_t n) const {
  if (little_ == (std::endian::native == std::endian::little)) return v;
  return __builtin_bswap64(v) >> (64 - 8 * n);
}

std::uint32_t CdrReader::u32() {
  align(4);
  std::uint32_t v;
  std::memcpy(&v, take(4), 4);
  return static_cast<std::uint32_t>(swap_if_needed(v, 4));
}

std::uint64_t CdrReader::u64() {
  align(8);
  std::uint64_t v;
  std::memcpy(&v, take(8), 8);
  return swap_if_needed(v, 8);
}

double CdrReader::f64() { return std::bit_cast<double>(u64()); }
float CdrReader::f32() { return std::bit_cast<float>(u32()); }

std::string CdrReader::string() {
  const std::uint32_t n = u32();
  if (n == 0) return {};  // some writers leave out the terminating NUL of an empty string
  const std::uint8_t* p = take(n);
  if (p[n - 1] != 0) fail("string is not NUL-terminated");
  return std::string(reinterpret_cast<const char*>(p), n - 1);
}

std::size_t CdrReader::sequence_length(std::size_t min_item_bytes) {
  const std::uint32_t n = u32();
  if (min_item_bytes > 0 && n > (size_ - pos_) / min_item_bytes) {
    fail("sequence of " + std::to_string(n) + " items runs past the payload end");
  }
  return n;
}

const std::uint8_t* CdrReader::bytes(std::size_t& n) {
  n = sequence_length(1);
  return take(n);
}

std::vector<double> CdrReader::f64_sequence() {
  std::vector<double> out(sequence_length(8));
  for (double& v : out) v = f64();
  return out;
}

void CdrReader::f64_array(double* out, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) out[i] = f64();
}

}  // namespace stillslam
