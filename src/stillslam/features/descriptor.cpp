#include "stillslam/features/descriptor.h"

#include <bit>
#include <cstring>

namespace stillslam {

int descriptor_distance(const std::uint8_t* a, const std::uint8_t* b) {
  int distance = 0;
  for (int i = 0; i < kDescriptorBytes; i += 8) {
    std::uint64_t wa, wb;
    std::memcpy(&wa, a + i, 8);
    std::memcpy(&wb, b + i, 8);
    distance += std::popcount(wa ^ wb);
  }
  return distance;
}

int descriptor_distance(const cv::Mat& a, const cv::Mat& b) {
  CV_Assert(a.type() == CV_8UC1 && b.type() == CV_8UC1 && a.total() == kDescriptorBytes &&
            b.total() == kDescriptorBytes && a.isContinuous() && b.isContinuous());
  return descriptor_distance(a.ptr<std::uint8_t>(), b.ptr<std::uint8_t>());
}

}  // namespace stillslam
