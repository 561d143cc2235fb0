#include "stillslam/features/descriptor_matcher.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stillslam/core/check.h"
#include "stillslam/features/descriptor.h"

namespace stillslam {

void MatchCandidates::Best::offer(int i, int d) {
  if (d < distance) {
    second = distance;
    distance = d;
    index = i;
  } else if (d < second) {
    second = d;
  }
}

MatchCandidates::MatchCandidates(std::size_t query_rows, std::size_t train_rows)
    : best_for_query_(query_rows), best_for_train_(train_rows) {}

void MatchCandidates::offer(int query, int train, int distance) {
  best_for_query_[static_cast<std::size_t>(query)].offer(train, distance);
  best_for_train_[static_cast<std::size_t>(train)].offer(query, distance);
}

std::vector<cv::DMatch> MatchCandidates::matches(const DescriptorMatchOptions& options) const {
  std::vector<cv::DMatch> out;
  for (std::size_t q = 0; q < best_for_query_.size(); ++q) {
    const Best& b = best_for_query_[q];
    if (b.index < 0 || b.distance > options.max_distance) continue;
    if (options.ratio < 1.f && b.second != std::numeric_limits<int>::max() &&
        static_cast<float>(b.distance) >= options.ratio * static_cast<float>(b.second)) {
      continue;
    }
    if (options.cross_check && best_for_train_[static_cast<std::size_t>(b.index)].index != static_cast<int>(q)) {
      continue;
    }
    out.emplace_back(static_cast<int>(q), b.index, static_cast<float>(b.distance));
  }
  return out;
}

std::vector<cv::DMatch> match_descriptors(const cv::Mat& query, const cv::Mat& train,
                                          const DescriptorMatchOptions& options) {
  if (query.empty() || train.empty()) return {};
  STILLSLAM_CHECK_EQ(query.type(), CV_8UC1, "match_descriptors: query rows must be 32-byte ORB descriptors");
  STILLSLAM_CHECK_EQ(query.cols, kDescriptorBytes, "match_descriptors: query rows must be 32-byte ORB descriptors");
  STILLSLAM_CHECK_EQ(train.type(), CV_8UC1, "match_descriptors: train rows must be 32-byte ORB descriptors");
  STILLSLAM_CHECK_EQ(train.cols, kDescriptorBytes, "match_descriptors: train rows must be 32-byte ORB descriptors");
  MatchCandidates candidates(static_cast<std::size_t>(query.rows), static_cast<std::size_t>(train.rows));
  for (int q = 0; q < query.rows; ++q) {
    const std::uint8_t* a = query.ptr<std::uint8_t>(q);
    for (int t = 0; t < train.rows; ++t) candidates.offer(q, t, descriptor_distance(a, train.ptr<std::uint8_t>(t)));
  }
  return candidates.matches(options);
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
