#include "stillslam/features/descriptor_matcher.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stillslam/core/check.h"
#include "stillslam/features/descriptor.h"

namespace stillslam {
namespace {

struct Best {
  int index = -1;
  int distance = std::numeric_limits<int>::max();
  int second = std::numeric_limits<int>::max();
  void offer(int i, int d) {
    if (d < distance) {
      second = distance;
      distance = d;
      index = i;
    } else if (d < second) {
      second = d;
    }
  }
};

}  // namespace

std::vector<cv::DMatch> match_descriptors(const cv::Mat& query, const cv::Mat& train,
                                          const DescriptorMatchOptions& options) {
  std::vector<cv::DMatch> matches;
  if (query.empty() || train.empty()) return matches;
  STILLSLAM_CHECK_EQ(query.type(), CV_8UC1, "match_descriptors: query rows must be 32-byte ORB descriptors");
  STILLSLAM_CHECK_EQ(query.cols, kDescriptorBytes, "match_descriptors: query rows must be 32-byte ORB descriptors");
  STILLSLAM_CHECK_EQ(train.type(), CV_8UC1, "match_descriptors: train rows must be 32-byte ORB descriptors");
  STILLSLAM_CHECK_EQ(train.cols, kDescriptorBytes, "match_descriptors: train rows must be 32-byte ORB descriptors");
  std::vector<Best> best_for_query(static_cast<std::size_t>(query.rows));
  std::vector<Best> best_for_train(static_cast<std::size_t>(train.rows));
  for (int q = 0; q < query.rows; ++q) {
    const std::uint8_t* a = query.ptr<std::uint8_t>(q);
    for (int t = 0; t < train.rows; ++t) {
      const int d = descriptor_distance(a, train.ptr<std::uint8_t>(t));
      best_for_query[static_cast<std::size_t>(q)].offer(t, d);
      best_for_train[static_cast<std::size_t>(t)].offer(q, d);
    }
  }
  for (int q = 0; q < query.rows; ++q) {
    const Best& b = best_for_query[static_cast<std::size_t>(q)];
    if (b.index < 0 || b.distance > options.max_distance) continue;
    if (options.ratio < 1.f && b.second != std::numeric_limits<int>::max() &&
        static_cast<float>(b.distance) >= options.ratio * static_cast<float>(b.second)) {
      continue;
    }
    if (options.cross_check && best_for_train[static_cast<std::size_t>(b.index)].index != q) continue;
    matches.emplace_back(q, b.index, static_cast<float>(b.distance));
  }
  return matches;
}

std::vector<bool> rotation_consistent(const std::vector<float>& angle_differences_deg, int bins) {
  std::vector<bool> keep(angle_differences_deg.size(), false);
  if (bins < 1 || angle_differences_deg.empty()) return keep;
  std::vector<int> bin_of(angle_differences_deg.size());
  std::vector<int> counts(static_cast<std::size_t>(bins), 0);
  for (std::size_t i = 0; i < angle_differences_deg.size(); ++i) {
    float d = std::fmod(angle_differences_deg[i], 360.f);
    if (d < 0.f) d += 360.f;
    const int b = std::min(bins - 1, static_cast<int>(d * static_cast<float>(bins) / 360.f));
    bin_of[i] = b;
    ++counts[static_cast<std::size_t>(b)];
  }
  // Three most populated bins (ties: lower bin), the 2nd and 3rd only if they
  // hold at least 10% of the first.
  std::vector<int> order(static_cast<std::size_t>(bins));
  for (int b = 0; b < bins; ++b) order[static_cast<std::size_t>(b)] = b;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return counts[static_cast<std::size_t>(a)] > counts[static_cast<std::size_t>(b)];
  });
  std::vector<bool> good_bin(static_cast<std::size_t>(bins), false);
  const int top = counts[static_cast<std::size_t>(order[0])];
  for (int k = 0; k < std::min(3, bins); ++k) {
    const int c = counts[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])];
    if (c > 0 && (k == 0 || 10 * c >= top)) good_bin[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])] = true;
  }
  for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = good_bin[static_cast<std::size_t>(bin_of[i])];
  return keep;
}

}  // namespace stillslam
