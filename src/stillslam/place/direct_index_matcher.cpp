#include "stillslam/place/direct_index_matcher.h"

#include <algorithm>
#include <limits>

#include "stillslam/features/descriptor.h"

namespace stillslam {

std::vector<cv::DMatch> match_by_direct_index(const cv::Mat& query_descriptors, const FeatureVector& query_groups,
                                              const cv::Mat& train_descriptors, const FeatureVector& train_groups,
                                              const DescriptorMatchOptions& options) {
  constexpr int kNone = std::numeric_limits<int>::max();
  struct Best {
    int index = -1;
    int distance = kNone;
  };
  std::vector<Best> best_of_train(static_cast<std::size_t>(train_descriptors.rows));
  std::vector<cv::DMatch> candidates;

  auto q = query_groups.groups.begin();
  auto t = train_groups.groups.begin();
  while (q != query_groups.groups.end() && t != train_groups.groups.end()) {
    if (q->node < t->node) { ++q; continue; }
    if (t->node < q->node) { ++t; continue; }
    for (std::uint32_t qi : q->features) {
      int best = kNone, second = kNone, best_index = -1;
      for (std::uint32_t ti : t->features) {
        const int d = descriptor_distance(query_descriptors.ptr<std::uint8_t>(static_cast<int>(qi)),
                                          train_descriptors.ptr<std::uint8_t>(static_cast<int>(ti)));
        if (d < best) {
          second = best;
          best = d;
          best_index = static_cast<int>(ti);
        } else if (d < second) {
          second = d;
        }
        Best& bt = best_of_train[ti];
        if (d < bt.distance) bt = {static_cast<int>(qi), d};
      }
      if (best_index < 0 || best > options.max_distance) continue;
      if (options.ratio < 1.0f && second != kNone &&
          static_cast<float>(best) >= options.ratio * static_cast<float>(second))
        continue;
      candidates.emplace_back(static_cast<int>(qi), best_index, static_cast<float>(best));
    }
    ++q;
    ++t;
  }
  if (options.cross_check)
    std::erase_if(candidates, [&](const cv::DMatch& m) {
      return best_of_train[static_cast<std::size_t>(m.trainIdx)].index != m.queryIdx;
    });
  std::sort(candidates.begin(), candidates.end(),
            [](const cv::DMatch& a, const cv::DMatch& b) { return a.queryIdx < b.queryIdx; });
  return candidates;
}

}  // namespace stillslam
