#include "stillslam/features/orientation.h"

#include <cmath>

namespace stillslam {

std::vector<int> disc_half_widths(int radius) {
  std::vector<int> half(static_cast<std::size_t>(radius) + 1);
  for (int v = 0; v <= radius; ++v) {
    int u = 0;
    while ((u + 1) * (u + 1) + v * v <= radius * radius) ++u;
    half[static_cast<std::size_t>(v)] = u;
  }
  return half;
}

void compute_orientations(const cv::Mat& image, std::vector<cv::KeyPoint>& keypoints) {
  const std::vector<int> half = disc_half_widths(kOrientationRadius);
  const int step = static_cast<int>(image.step1());
  for (auto& kp : keypoints) {
    const int cx = cvRound(kp.pt.x), cy = cvRound(kp.pt.y);
    const std::uint8_t* center = image.ptr<std::uint8_t>(cy) + cx;
    long m10 = 0, m01 = 0;
    for (int u = -kOrientationRadius; u <= kOrientationRadius; ++u) m10 += u * center[u];
    // Rows +v and -v together: their x moments add, their y moments subtract.
    for (int v = 1; v <= kOrientationRadius; ++v) {
      const int w = half[static_cast<std::size_t>(v)];
      long row_sum_diff = 0;
      for (int u = -w; u <= w; ++u) {
        const int below = center[u + v * step], above = center[u - v * step];
        row_sum_diff += below - above;
        m10 += u * (below + above);
      }
      m01 += v * row_sum_diff;
    }
    kp.angle = cv::fastAtan2(static_cast<float>(m01), static_cast<float>(m10));
  }
}

}  // namespace stillslam
