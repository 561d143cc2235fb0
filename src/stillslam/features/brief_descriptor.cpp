#include "stillslam/features/brief_descriptor.h"

#include <cmath>
#include <numbers>

namespace stillslam {

void compute_brief(const cv::Mat& smoothed, const std::vector<cv::KeyPoint>& keypoints,
                   const BriefPattern& pattern, cv::Mat& descriptors, int row_offset) {
  CV_Assert(smoothed.type() == CV_8UC1 && descriptors.type() == CV_8UC1 && descriptors.cols == 32 &&
            descriptors.rows >= row_offset + static_cast<int>(keypoints.size()));
  const int step = static_cast<int>(smoothed.step1());
  for (std::size_t k = 0; k < keypoints.size(); ++k) {
    const cv::KeyPoint& kp = keypoints[k];
    const double angle = kp.angle * std::numbers::pi / 180.0;
    const float c = static_cast<float>(std::cos(angle)), s = static_cast<float>(std::sin(angle));
    const std::uint8_t* center = smoothed.ptr<std::uint8_t>(cvRound(kp.pt.y)) + cvRound(kp.pt.x);
    // Rotated sample offset (x, y) -> R(angle) * (x, y), rounded to a pixel.
    auto sample = [&](int x, int y) {
      const int rx = cvRound(static_cast<float>(x) * c - static_cast<float>(y) * s);
      const int ry = cvRound(static_cast<float>(x) * s + static_cast<float>(y) * c);
      return center[ry * step + rx];
    };
    std::uint8_t* out = descriptors.ptr<std::uint8_t>(row_offset + static_cast<int>(k));
    for (int byte = 0; byte < 32; ++byte) {
      std::uint8_t value = 0;
      for (int bit = 0; bit < 8; ++bit) {
        const BriefPair& p = pattern.pairs[static_cast<std::size_t>(byte * 8 + bit)];
        if (sample(p.x1, p.y1) < sample(p.x2, p.y2)) value |= static_cast<std::uint8_t>(1u << bit);
      }
      out[byte] = value;
    }
  }
}

}  // namespace stillslam
