#pragma once
// Little-endian byte buffer writer/reader for the map file (map_file.cpp).
// The reader checks every read against the buffer end and reports running
// past it through a callback-built Error, so a truncated or corrupt payload
// never reads out of bounds.
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

#include "stillslam/core/error.h"

namespace stillslam::map_file_detail {

static_assert(std::endian::native == std::endian::little, "map files are little-endian");

class ByteWriter {
 public:
  template <typename T>
  void put(T value) {
    static_assert(std::is_arithmetic_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void put_bytes(const void* data, std::size_t n) { bytes_.append(static_cast<const char*>(data), n); }
  void put_string(const std::string& s) {
    put(static_cast<std::uint32_t>(s.size()));
    bytes_.append(s);
  }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

class ByteReader {
 public:
  // `what` names the file in errors.
  ByteReader(const char* data, std::size_t size, std::string what) : p_(data), end_(data + size), what_(std::move(what)) {}

  template <typename T>
  T get() {
    static_assert(std::is_arithmetic_v<T>);
    T value;
    std::memcpy(&value, take(sizeof(T)), sizeof(T));
    return value;
  }
  const char* get_bytes(std::size_t n) { return take(n); }
  std::string get_string() {
    const auto n = get<std::uint32_t>();
    return std::string(take(n), n);
  }
  // A count of items of at least `min_item_bytes` each that must fit in the
  // rest of the buffer (a corrupt count fails here, not in a huge allocation).
  std::size_t get_count(std::size_t min_item_bytes) {
    const auto n = get<std::uint32_t>();
    if (min_item_bytes > 0 && n > remaining() / min_item_bytes) fail("item count " + std::to_string(n) + " past the end");
    return n;
  }
  std::size_t remaining() const { return static_cast<std::size_t>(end_ - p_); }
  [[noreturn]] void fail(const std::string& detail) const {
    throw Error(what_ + ": corrupt map file (" + detail + "); re-create it with `stillslam run --save-map`");
  }

 private:
  const char* take(std::size_t n) {
    if (n > remaining()) fail("unexpected end of data");
    const char* p = p_;
    p_ += n;
    return p;
  }

  const char* p_;
  const char* end_;
  std::string what_;
};

}  // namespace stillslam::map_file_detail
