// PlaceRecognizer: indexing keyframes, relocalization candidates, loop
// candidates (covisible exclusion, minimum score from the neighbours), erase.
#include <gtest/gtest.h>

#include "loop/loop_scene.h"
#include "stillslam/core/error.h"
#include "stillslam/loop/place_recognizer.h"

namespace stillslam {
namespace {

class PlaceRecognizerTest : public ::testing::Test {
 protected:
  PlaceRecognizerTest()
      : recognizer_(std::make_shared<const Vocabulary>(scene_.train_vocabulary())) {
    for (int i = 0; i < 12; ++i) recognizer_.add(*scene_.add_keyframe(i));
  }
  test::LoopScene scene_;
  PlaceRecognizer recognizer_;
};

TEST_F(PlaceRecognizerTest, RelocalizationCandidatesStartWithTheSamePlace) {
  ASSERT_EQ(recognizer_.size(), 12u);
  const KeyFramePtr kf5 = scene_.map().keyframe(5);
  const BowDescription d = recognizer_.describe(PlaceRecognizer::descriptors_of(*kf5));
  const auto candidates = recognizer_.relocalization_candidates(d.bow);
  ASSERT_FALSE(candidates.empty());
  EXPECT_EQ(candidates.front().id, 5u);
  EXPECT_NEAR(candidates.front().score, 1.0, 1e-9);
  // Neighbours on the circle come next; far keyframes share too few words.
  for (const auto& c : candidates) EXPECT_LE(std::abs(static_cast<int>(c.id) - 5), 3) << c.id;
  EXPECT_FALSE(recognizer_.description(5)->features.empty());

  recognizer_.erase(5);
  EXPECT_FALSE(recognizer_.contains(5));
  EXPECT_EQ(recognizer_.description(5), nullptr);
  const auto after = recognizer_.relocalization_candidates(d.bow);
  ASSERT_FALSE(after.empty());
  EXPECT_NE(after.front().id, 5u);
}

TEST_F(PlaceRecognizerTest, LoopCandidatesExcludeNeighboursAndScoreAboveTheWorstNeighbour) {
  const KeyFramePtr kf = scene_.map().keyframe(8);
  std::vector<KeyframeId> covisible;
  for (KeyFrame* k : kf->covisibles()) covisible.push_back(k->id());
  ASSERT_GE(covisible.size(), 6u);  // keyframes sharing >= 15 of its points: 2..7, 9..11
  for (KeyframeId id : covisible) EXPECT_LE(std::abs(static_cast<int>(id) - 8), 6);
  const double min_score = recognizer_.min_covisible_score(recognizer_.description(8)->bow, covisible);
  EXPECT_GT(min_score, 0.05);
  EXPECT_LT(min_score, 0.9);
  const auto candidates = recognizer_.loop_candidates(*kf, covisible, 0);
  for (const auto& c : candidates) {
    EXPECT_NE(c.id, 8u);
    EXPECT_EQ(std::count(covisible.begin(), covisible.end(), c.id), 0);
    EXPECT_GE(c.score, min_score);
  }
  // Without exclusions (but never itself) a direct neighbour is the best match.
  const auto all = recognizer_.loop_candidates(*kf, {}, 0);
  ASSERT_FALSE(all.empty());
  EXPECT_EQ(std::abs(static_cast<int>(all.front().id) - 8), 1);
  EXPECT_EQ(recognizer_.min_covisible_score(recognizer_.description(8)->bow, {}), 0.0);
}

TEST(PlaceRecognizer, RejectsAnEmptyVocabulary) {
  EXPECT_THROW(PlaceRecognizer(std::make_shared<const Vocabulary>()), Error);
}

}  // namespace
}  // namespace stillslam
