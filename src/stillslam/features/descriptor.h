#pragma once
// Hamming distance between 256-bit (32-byte) binary descriptors.
#include <cstdint>
#include <opencv2/core.hpp>

namespace stillslam {

inline constexpr int kDescriptorBytes = 32;

// a, b: single rows (1 x 32 CV_8U), e.g. descriptors.row(i).
int descriptor_distance(const cv::Mat& a, const cv::Mat& b);
// a, b: 32 bytes each.
int descriptor_distance(const std::uint8_t* a, const std::uint8_t* b);

}  // namespace stillslam
