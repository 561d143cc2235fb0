#pragma once
// Descriptor matching restricted by the direct index: features of two images
// are compared only when they fall under the same vocabulary node (ORB-SLAM's
// SearchByBoW idea without map points), so a 1000 x 1000 match costs a few
// percent of brute force.
#include <opencv2/core.hpp>
#include <vector>

#include "stillslam/features/descriptor_matcher.h"
#include "stillslam/place/bow_vector.h"

namespace stillslam {

// Same rules as match_descriptors (max distance, ratio to the second best,
// optional mutual best) but both the best and second best are searched only
// within shared groups. queryIdx/trainIdx index the descriptor rows; the
// result is sorted by queryIdx. Both feature vectors must come from the same
// vocabulary and direct-index level.
std::vector<cv::DMatch> match_by_direct_index(const cv::Mat& query_descriptors, const FeatureVector& query_groups,
                                              const cv::Mat& train_descriptors, const FeatureVector& train_groups,
                                              const DescriptorMatchOptions& options = {});

}  // namespace stillslam
