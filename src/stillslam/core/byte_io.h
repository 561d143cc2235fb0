#pragma once
// Little-endian byte buffer writer/reader for the project's binary files (map
// files, the vocabulary). The reader checks every read against the buffer end,
// so a truncated or corrupt file never reads out of bounds; the Error it then
// throws is built by the caller, which knows the file and how to fix it.
#include <bit>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "stillslam/core/error.h"

namespace stillslam {

static_assert(std::endian::native == std::endian::little, "the binary files are little-endian");

class ByteWriter {
 public:
  template <typename T>
  void put(T value) {
    static_assert(std::is_arithmetic_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  // Every element's bytes in order (numbers, or fixed-size arrays of them).
  template <typename T>
  void put_all(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    put_bytes(values.data(), sizeof(T) * values.size());
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

// Builds the Error a ByteReader throws from what went wrong (e.g. "unexpected
// end of data"); the caller's wording names the file and what to do.
using ByteReadError = std::function<Error(const std::string& detail)>;

class ByteReader {
 public:
  ByteReader(const char* data, std::size_t size, ByteReadError make_error)
      : p_(data), end_(data + size), make_error_(std::move(make_error)) {}

  template <typename T>
  T get() {
    static_assert(std::is_arithmetic_v<T>);
    T value;
    std::memcpy(&value, take(sizeof(T)), sizeof(T));
    return value;
  }
  // `n` elements into `values` (replacing its contents).
  template <typename T>
  void get_all(std::vector<T>& values, std::size_t n) {
    static_assert(std::is_trivially_copyable_v<T>);
    const char* p = take(sizeof(T) * n);
    values.resize(n);
    if (n > 0) std::memcpy(values.data(), p, sizeof(T) * n);
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
  [[noreturn]] void fail(const std::string& detail) const { throw make_error_(detail); }

 private:
  const char* take(std::size_t n) {
    if (n > remaining()) fail("unexpected end of data");
    const char* p = p_;
    p_ += n;
    return p;
  }

  const char* p_;
  const char* end_;
  ByteReadError make_error_;
};

}  // namespace stillslam
