#pragma once
// Brute-force descriptor matching helpers (for initialization, relocalization
// candidates, tests and tools; tracking uses FeatureGrid-guided search).
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

// ORB-SLAM's rotation consistency check: histogram of keypoint angle
// differences (train - query, degrees) in `bins` bins; returns a mask that
// keeps matches in the three most populated bins (a bin is dropped if it has
// fewer than 10% of the top bin's count).
std::vector<bool> rotation_consistent(const std::vector<float>& angle_differences_deg,
                                      int bins = 30);

}  // namespace stillslam
