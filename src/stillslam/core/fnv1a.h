#pragma once
// FNV-1a 64: the checksum of the project's binary files (vocabulary, maps)
// and the vocabulary fingerprint stored in map files. Not cryptographic: it
// catches truncation and flipped bytes, which is all those files need.
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace stillslam {

class Fnv1a {
 public:
  void add_bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) {
      h_ ^= p[i];
      h_ *= 0x100000001b3ULL;
    }
  }
  // The value's bytes as stored in memory (the files are little-endian).
  template <typename T>
  void add(const T& value) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    add_bytes(bytes, sizeof(T));
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

inline std::uint64_t fnv1a(const void* data, std::size_t n) {
  Fnv1a h;
  h.add_bytes(data, n);
  return h.value();
}

}  // namespace stillslam
