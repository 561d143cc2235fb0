#include "stillslam/features/brief_descriptor.h"

#include <array>
#include <cmath>
#include <numbers>

#include "stillslam/core/check.h"

namespace stillslam {

void compute_brief(const cv::Mat& smoothed, const std::vector<cv::KeyPoint>& keypoints,
                   const BriefPattern& pattern, cv::Mat& descriptors, int row_offset) {
  STILLSLAM_CHECK_EQ(smoothed.type(), CV_8UC1, "compute_brief: the smoothed level must be 8-bit grey");
  STILLSLAM_CHECK(descriptors.type() == CV_8UC1 && descriptors.cols == 32,
                  "compute_brief: descriptors must be N x 32 CV_8U");
  STILLSLAM_CHECK_LE(row_offset + static_cast<int>(keypoints.size()), descriptors.rows,
                     "compute_brief: one descriptor row per keypoint from row_offset on");
  constexpr int kPoints = 2 * BriefPattern::kNumPairs;
  // Pattern as separate float coordinate arrays (point 2i, 2i+1 = pair i), so
  // the per-keypoint rotation below is a straight vectorizable loop.
  std::array<float, kPoints> px{}, py{};
  for (int i = 0; i < BriefPattern::kNumPairs; ++i) {
    const BriefPair& p = pattern.pairs[static_cast<std::size_t>(i)];
    px[static_cast<std::size_t>(2 * i)] = p.x1;
    py[static_cast<std::size_t>(2 * i)] = p.y1;
    px[static_cast<std::size_t>(2 * i + 1)] = p.x2;
    py[static_cast<std::size_t>(2 * i + 1)] = p.y2;
  }
  const int step = static_cast<int>(smoothed.step1());
  std::array<int, kPoints> offset{};
  for (std::size_t k = 0; k < keypoints.size(); ++k) {
    const cv::KeyPoint& kp = keypoints[k];
    const double angle = kp.angle * std::numbers::pi / 180.0;
    const float c = static_cast<float>(std::cos(angle)), s = static_cast<float>(std::sin(angle));
    // Rotated sample offsets R(angle) * (x, y), rounded to pixels.
    for (int i = 0; i < kPoints; ++i) {
      const float rx = px[static_cast<std::size_t>(i)] * c - py[static_cast<std::size_t>(i)] * s;
      const float ry = px[static_cast<std::size_t>(i)] * s + py[static_cast<std::size_t>(i)] * c;
      offset[static_cast<std::size_t>(i)] = cvRound(ry) * step + cvRound(rx);
    }
    const std::uint8_t* center = smoothed.ptr<std::uint8_t>(cvRound(kp.pt.y)) + cvRound(kp.pt.x);
    std::uint8_t* out = descriptors.ptr<std::uint8_t>(row_offset + static_cast<int>(k));
    const int* o = offset.data();
    for (int byte = 0; byte < 32; ++byte, o += 16) {
      unsigned value = 0;
      for (int bit = 0; bit < 8; ++bit) {
        value |= static_cast<unsigned>(center[o[2 * bit]] < center[o[2 * bit + 1]]) << bit;
      }
      out[byte] = static_cast<std::uint8_t>(value);
    }
  }
}

}  // namespace stillslam
