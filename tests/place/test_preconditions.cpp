// place entry points reject inconsistent input with a PreconditionError.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "common/precondition.h"
#include "stillslam/place/vocabulary.h"

namespace stillslam {
namespace {

TEST(PlacePreconditions, TransformNeeds32ByteDescriptors) {
  const Vocabulary vocabulary = Vocabulary::train({cv::Mat(20, 32, CV_8UC1, cv::Scalar(7))}, VocabularyOptions{});
  test::expect_precondition([&] { vocabulary.transform(cv::Mat(5, 16, CV_8UC1, cv::Scalar(1))); },
                            "src/stillslam/place/vocabulary.cpp",
                            "Vocabulary::transform: pass N x 32 CV_8U ORB descriptors (check failed: "
                            "descriptors.cols == 32, 16 vs 32)");
}

TEST(PlacePreconditions, AnEmptyVocabularyHasNoWords) {
  test::expect_precondition([&] { Vocabulary().transform(cv::Mat(5, 32, CV_8UC1, cv::Scalar(1))); },
                            "src/stillslam/place/vocabulary.cpp",
                            "Vocabulary::word_of: the vocabulary is empty (train or load one first) (check failed: "
                            "!empty())");
}

}  // namespace
}  // namespace stillslam
