#pragma once
// Repeatability and matching scores of ORB features between an image and a
// warped copy whose level-0 pixel mapping is known.
#include <functional>
#include <opencv2/core.hpp>

#include "stillslam/features/descriptor_matcher.h"
#include "stillslam/features/orb_features.h"

namespace stillslam::test {

using PointMap = std::function<cv::Point2f(const cv::Point2f&)>;

struct InvarianceScores {
  int visible = 0;          // keypoints of A that map inside B (20 px margin)
  double repeatability = 0; // fraction of those with a B keypoint within 2 px
  int matches = 0;          // mutual best descriptor matches (distance <= 64)
  double match_precision = 0;  // fraction of matches landing within 3 px of the mapped point
  int correct_matches = 0;
};

inline InvarianceScores invariance_scores(const OrbFeatures& a, const OrbFeatures& b, const cv::Size& b_size,
                                          const PointMap& a_to_b) {
  InvarianceScores s;
  int repeated = 0;
  for (const auto& ka : a.keypoints) {
    const cv::Point2f p = a_to_b(ka.pt);
    if (p.x < 20 || p.y < 20 || p.x > b_size.width - 20 || p.y > b_size.height - 20) continue;
    ++s.visible;
    for (const auto& kb : b.keypoints) {
      if (cv::norm(kb.pt - p) <= 2.0) {
        ++repeated;
        break;
      }
    }
  }
  s.repeatability = s.visible ? static_cast<double>(repeated) / s.visible : 0;
  const auto m = match_descriptors(a.descriptors, b.descriptors, {.max_distance = 64, .ratio = 1.f, .cross_check = true});
  s.matches = static_cast<int>(m.size());
  for (const auto& match : m) {
    const cv::Point2f p = a_to_b(a.keypoints[static_cast<std::size_t>(match.queryIdx)].pt);
    s.correct_matches += cv::norm(b.keypoints[static_cast<std::size_t>(match.trainIdx)].pt - p) <= 3.0;
  }
  s.match_precision = s.matches ? static_cast<double>(s.correct_matches) / s.matches : 0;
  return s;
}

}  // namespace stillslam::test
