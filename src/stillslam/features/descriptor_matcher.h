#pragma once
// Brute-force descriptor matching helpers (for initialization, relocalization
// candidates, tests and tools; tracking uses FeatureGrid-guided search).
#include <cstddef>
#include <limits>
#include <opencv2/core.hpp>
#include <vector>

namespace stillslam {

struct DescriptorMatchOptions {
  int max_distance = 50;         // reject matches with a larger Hamming distance
  float ratio = 0.8f;            // best < ratio * second best (1 disables)
  bool cross_check = true;       // keep only mutual best matches
};

// queryIdx indexes `query` rows, trainIdx indexes `train` rows; sorted by
// queryIdx. Both are N x 32 CV_8U.
std::vector<cv::DMatch> match_descriptors(const cv::Mat& query, const cv::Mat& train,
                                          const DescriptorMatchOptions& options = {});

// The best and second-best distance offered to each query and train row, and
// the matches they give: match_descriptors offers every pair, a guided
// matcher only the pairs it compares. Ties keep the first pair offered.
class MatchCandidates {
 public:
  MatchCandidates(std::size_t query_rows, std::size_t train_rows);
  void offer(int query, int train, int distance);
  // DescriptorMatchOptions' distance bound, ratio test and cross check;
  // sorted by queryIdx.
  std::vector<cv::DMatch> matches(const DescriptorMatchOptions& options) const;

 private:
  struct Best {
    int index = -1;
    int distance = std::numeric_limits<int>::max();
    int second = std::numeric_limits<int>::max();
    void offer(int i, int d);
  };
  std::vector<Best> best_for_query_;
  std::vector<Best> best_for_train_;
};

// ORB-SLAM's rotation consistency check: histogram of keypoint angle
// differences (train - query, degrees) in `bins` bins; returns a mask that
// keeps matches in the three most populated bins (a bin is dropped if it has
// fewer than 10% of the top bin's count).
std::vector<bool> rotation_consistent(const std::vector<float>& angle_differences_deg,
                                      int bins = 30);

}  // namespace stillslam
