// features entry points reject inconsistent input with a PreconditionError.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "common/precondition.h"
#include "stillslam/features/descriptor_matcher.h"
#include "stillslam/features/orb_extractor.h"
#include "stillslam/features/stereo_matcher.h"

namespace stillslam {
namespace {

TEST(FeaturesPreconditions, MatchingNeeds32ByteDescriptors) {
  const cv::Mat orb(4, 32, CV_8UC1, cv::Scalar(7));
  const cv::Mat short_rows(4, 16, CV_8UC1, cv::Scalar(7));
  test::expect_precondition([&] { match_descriptors(orb, short_rows); },
                            "src/stillslam/features/descriptor_matcher.cpp",
                            "match_descriptors: train rows must be 32-byte ORB descriptors (check failed: "
                            "train.cols == kDescriptorBytes, 16 vs 32)");
}

TEST(FeaturesPreconditions, ExclusionMaskMustMatchTheImage) {
  const OrbExtractor extractor{OrbOptions{}};
  const cv::Mat image(120, 160, CV_8UC1, cv::Scalar(0));
  test::expect_precondition([&] { extractor.extract(image, cv::Mat1b(120, 100, uchar{0}), nullptr); },
                            "src/stillslam/features/orb_extractor.cpp",
                            "ORB extraction: the exclusion mask must have the image's size (check failed: "
                            "exclude.cols == gray.cols, 100 vs 160)");
}

TEST(FeaturesPreconditions, DepthStereoNeedsOneUndistortedKeypointPerRawOne) {
  const std::vector<cv::KeyPoint> two = {cv::KeyPoint(5, 5, 31), cv::KeyPoint(9, 9, 31)};
  const std::vector<cv::KeyPoint> one = {cv::KeyPoint(5, 5, 31)};
  test::expect_precondition([&] { stereo_from_depth(two, one, cv::Mat(40, 40, CV_32FC1, cv::Scalar(1)), 40.0); },
                            "src/stillslam/features/stereo_matcher.cpp",
                            "stereo_from_depth: one undistorted keypoint per raw keypoint (check failed: "
                            "raw.size() == undistorted.size(), 2 vs 1)");
}

}  // namespace
}  // namespace stillslam
