#pragma once
// 256-bit ORB descriptors as four 64-bit words: the unit the vocabulary
// clusters and compares. Kept inline because training and transform spend
// nearly all their time in these few operations.
#include <array>
#include <cstdint>
#include <cstring>
#include <opencv2/core.hpp>
#include <vector>

namespace stillslam::place_detail {

using Descriptor256 = std::array<std::uint64_t, 4>;

// Branch-free bit count: the build targets baseline x86-64 (no POPCNT), where
// std::popcount is a library call.
inline int bit_count(std::uint64_t x) {
  x = x - ((x >> 1) & 0x5555555555555555ULL);
  x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
  x = (x + (x >> 4)) & 0x0F0F0F0F0F0F0F0FULL;
  return static_cast<int>((x * 0x0101010101010101ULL) >> 56);
}

inline int hamming(const Descriptor256& a, const Descriptor256& b) {
  return bit_count(a[0] ^ b[0]) + bit_count(a[1] ^ b[1]) + bit_count(a[2] ^ b[2]) + bit_count(a[3] ^ b[3]);
}

inline Descriptor256 pack(const std::uint8_t* bytes) {
  Descriptor256 d;
  std::memcpy(d.data(), bytes, sizeof(d));
  return d;
}

// Rows of an N x 32 CV_8U matrix. Throws stillslam::Error for any other shape
// or type (`what` names the input in the message).
std::vector<Descriptor256> pack_rows(const cv::Mat& descriptors, const char* what);

// Per-bit vote counter for the k-majority centre of a cluster.
class BitMajority {
 public:
  void add(const Descriptor256& d) {
    for (int w = 0; w < 4; ++w) {
      const std::uint64_t x = d[w];
      int* c = counts_.data() + 64 * w;
      for (int b = 0; b < 64; ++b) c[b] += static_cast<int>((x >> b) & 1U);
    }
    ++n_;
  }
  int size() const { return n_; }
  // A bit is set when more than half of the members have it set.
  Descriptor256 centre() const {
    Descriptor256 d{};
    for (int w = 0; w < 4; ++w)
      for (int b = 0; b < 64; ++b)
        if (2 * counts_[64 * w + b] > n_) d[w] |= (std::uint64_t{1} << b);
    return d;
  }

 private:
  std::array<int, 256> counts_{};
  int n_ = 0;
};

}  // namespace stillslam::place_detail
