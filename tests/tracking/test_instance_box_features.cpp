// The motion stage's features inside masked instances, extracted on their
// boxes only (tracking/instance_box_features.h).
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "stillslam/features/orb_extractor.h"
#include "stillslam/tracking/instance_box_features.h"
#include "common/blurred_noise.h"

namespace stillslam {
namespace {

TEST(InstanceBoxFeatures, BoxesArePaddedClippedAndMergedWhenTheyOverlap) {
  const std::vector<cv::Rect> boxes = {{100, 100, 50, 50}, {170, 100, 50, 50}, {400, 300, 40, 40}, {620, 0, 30, 30}};
  const std::vector<cv::Rect> merged = merge_instance_boxes(boxes, 16, cv::Size(640, 480));
  ASSERT_EQ(merged.size(), 3u);
  // The first two are 20 px apart: padded by 16 they overlap and become one.
  EXPECT_EQ(merged[0], cv::Rect(84, 84, 152, 82));
  EXPECT_EQ(merged[1], cv::Rect(384, 284, 72, 72));
  EXPECT_EQ(merged[2], cv::Rect(604, 0, 36, 46));  // clipped at the image border
  EXPECT_TRUE(merge_instance_boxes({cv::Rect()}, 0, cv::Size(640, 480)).empty());
  // A merged box that reaches a third merges with it too.
  const auto chain = merge_instance_boxes({{0, 0, 10, 10}, {30, 0, 10, 10}, {12, 0, 16, 10}}, 2, cv::Size(640, 480));
  ASSERT_EQ(chain.size(), 1u);
  EXPECT_EQ(chain[0], cv::Rect(0, 0, 42, 12));
}

TEST(InstanceBoxFeatures, FeaturesOnlyOnTheInstancesPixelsAsManyAsAFullFramePass) {
  const cv::Mat gray = test::blurred_noise(480, 640, 3);
  cv::Mat1b inside = cv::Mat1b::zeros(480, 640);
  const cv::Rect person(60, 80, 140, 300), box(420, 260, 90, 90);
  inside(person).setTo(255);
  inside(box).setTo(255);
  OrbOptions orb;
  const int budget = 200;
  const OrbFeatures f =
      extract_in_boxes(orb, budget, gray, inside, merge_instance_boxes({person, box}, 32, gray.size()));
  ASSERT_EQ(static_cast<int>(f.keypoints.size()), f.descriptors.rows);
  for (const cv::KeyPoint& kp : f.keypoints) {
    const cv::Point p(static_cast<int>(kp.pt.x), static_cast<int>(kp.pt.y));
    ASSERT_TRUE(person.contains(p) || box.contains(p)) << kp.pt;
  }
  std::size_t on_box = 0;
  for (const cv::KeyPoint& kp : f.keypoints) on_box += box.contains(cv::Point(kp.pt));
  EXPECT_GT(on_box, 10u);
  EXPECT_GT(f.keypoints.size() - on_box, 60u);
  // What the whole-pyramid pass with the same budget finds inside the mask.
  orb.n_features = budget;
  const OrbFeatures full = OrbExtractor(orb).extract(gray, inside == 0, nullptr);
  EXPECT_GT(f.keypoints.size(), full.keypoints.size() * 0.7);
  EXPECT_LT(f.keypoints.size(), static_cast<std::size_t>(budget) + 10);
  // A level-0 feature inside a box has the descriptor the full pass gives it.
  int same = 0, compared = 0;
  for (std::size_t i = 0; i < f.keypoints.size(); ++i) {
    if (f.keypoints[i].octave != 0) continue;
    for (std::size_t j = 0; j < full.keypoints.size(); ++j) {
      if (full.keypoints[j].octave != 0 || cv::norm(full.keypoints[j].pt - f.keypoints[i].pt) > 0.01) continue;
      ++compared;
      same += cv::norm(f.descriptors.row(static_cast<int>(i)), full.descriptors.row(static_cast<int>(j)),
                       cv::NORM_HAMMING) == 0;
    }
  }
  EXPECT_GT(compared, 10);
  EXPECT_EQ(same, compared);
}

// A small object next to a large person: by area alone it would get 6 % of
// the budget (12 features); it gets at least half an equal share.
TEST(InstanceBoxFeatures, ASmallBoxGetsAtLeastHalfAnEqualShare) {
  const cv::Mat gray = test::blurred_noise(480, 640, 4);
  cv::Mat1b inside = cv::Mat1b::zeros(480, 640);
  const cv::Rect person(40, 40, 300, 400), box(480, 200, 60, 60);
  inside(person).setTo(255);
  inside(box).setTo(255);
  const OrbFeatures f =
      extract_in_boxes(OrbOptions{}, 200, gray, inside, merge_instance_boxes({person, box}, 32, gray.size()));
  std::size_t on_box = 0;
  for (const cv::KeyPoint& kp : f.keypoints) on_box += box.contains(cv::Point(kp.pt));
  EXPECT_GT(on_box, 30u);
  EXPECT_LE(f.keypoints.size(), 300u);  // the budget plus at most half of it
}

TEST(InstanceBoxFeatures, ASmallBoxUsesFewerLevelsAndStillWorks) {
  const cv::Mat gray = test::blurred_noise(480, 640, 4);
  cv::Mat1b inside = cv::Mat1b::zeros(480, 640);
  inside(cv::Rect(300, 200, 30, 30)).setTo(255);
  const OrbFeatures f =
      extract_in_boxes(OrbOptions{}, 50, gray, inside, merge_instance_boxes({{300, 200, 30, 30}}, 32, gray.size()));
  EXPECT_GT(f.keypoints.size(), 3u);
  // 94 px padded: levels down to 54 px (3 of them above level 0), not the 8 of a frame.
  for (const cv::KeyPoint& kp : f.keypoints) EXPECT_LE(kp.octave, 3);
  EXPECT_TRUE(extract_in_boxes(OrbOptions{}, 50, gray, inside, {}).keypoints.empty());
}

}  // namespace
}  // namespace stillslam
