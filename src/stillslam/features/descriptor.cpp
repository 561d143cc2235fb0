#include "stillslam/features/descriptor.h"

#include <cstring>

#include "stillslam/core/check.h"

namespace stillslam {
namespace {

// Branch-free bit count (SWAR). The build targets baseline x86-64 without the
// POPCNT instruction, where std::popcount becomes a slow library call; this
// is ~10x faster there and compiles to a handful of ALU operations anywhere.
inline int bit_count(std::uint64_t x) {
  x = x - ((x >> 1) & 0x5555555555555555ULL);
  x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
  x = (x + (x >> 4)) & 0x0F0F0F0F0F0F0F0FULL;
  return static_cast<int>((x * 0x0101010101010101ULL) >> 56);
}

}  // namespace

int descriptor_distance(const std::uint8_t* a, const std::uint8_t* b) {
  int distance = 0;
  for (int i = 0; i < kDescriptorBytes; i += 8) {
    std::uint64_t wa, wb;
    std::memcpy(&wa, a + i, 8);
    std::memcpy(&wb, b + i, 8);
    distance += bit_count(wa ^ wb);
  }
  return distance;
}

int descriptor_distance(const cv::Mat& a, const cv::Mat& b) {
  STILLSLAM_CHECK(a.type() == CV_8UC1 && a.total() == kDescriptorBytes && a.isContinuous(),
                  "descriptor_distance: pass one continuous 32-byte ORB descriptor");
  STILLSLAM_CHECK(b.type() == CV_8UC1 && b.total() == kDescriptorBytes && b.isContinuous(),
                  "descriptor_distance: pass one continuous 32-byte ORB descriptor");
  return descriptor_distance(a.ptr<std::uint8_t>(), b.ptr<std::uint8_t>());
}

}  // namespace stillslam
