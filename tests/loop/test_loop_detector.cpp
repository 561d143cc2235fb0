// LoopDetector on the synthetic circle: with temporal consistency alone the
// revisit is found only after the candidate group has been consistent over 3
// consecutive keyframes, and an interruption resets the count; with covisible
// confirmation (the default) the first candidate keyframe is accepted when
// its neighbours see the loop too. The SE3 it returns removes the drift.
#include <gtest/gtest.h>

#include "loop/loop_scene.h"
#include "stillslam/loop/loop_detector.h"

namespace stillslam {
namespace {

constexpr int kKeyframes = 42;  // 410 degrees: the last 6 keyframes revisit the start

class LoopDetectorTest : public ::testing::Test {
 protected:
  LoopDetectorTest() : recognizer_(std::make_shared<const Vocabulary>(scene_.train_vocabulary())) {
    for (int i = 0; i < kKeyframes; ++i) keyframes_.push_back(scene_.add_keyframe(i));
  }
  // Detection on keyframe i, then indexing it (the loop closer's order).
  std::optional<LoopDetection> feed(LoopDetector& detector, int i) {
    auto d = detector.detect(scene_.map(), *keyframes_[static_cast<std::size_t>(i)]);
    recognizer_.add(*keyframes_[static_cast<std::size_t>(i)]);
    return d;
  }
  test::LoopScene scene_;
  PlaceRecognizer recognizer_;
  std::vector<KeyFramePtr> keyframes_;
};

LoopDetectorOptions temporal_consistency_only() {
  LoopDetectorOptions o;
  o.confirmation_neighbours = 0;
  return o;
}

TEST_F(LoopDetectorTest, FindsTheRevisitAfterThreeConsistentKeyframes) {
  LoopDetector detector(recognizer_, temporal_consistency_only());
  std::optional<LoopDetection> loop;
  int found_at = -1;
  for (int i = 0; i < kKeyframes && !loop; ++i) {
    loop = feed(detector, i);
    if (loop) found_at = i;
  }
  ASSERT_TRUE(loop);
  // Keyframe 32 is the first whose view overlaps keyframe 0's enough to be a
  // candidate; 32, 33, 34 make three consistent keyframes.
  EXPECT_EQ(found_at, 34);
  EXPECT_LE(loop->loop->id(), 2u);
  EXPECT_GE(loop->inliers, 200);
  // The corrected pose is the true pose up to the (small) drift of the loop keyframe's area.
  const Eigen::Isometry3d truth = scene_.true_T_world_cam(found_at);
  const double corrected_error = (loop->T_world_query_corrected.translation() - truth.translation()).norm();
  const double drifted_error = (keyframes_[34]->camera_center() - truth.translation()).norm();
  EXPECT_GT(drifted_error, 0.1);
  EXPECT_LT(corrected_error, 0.01);
  const auto matched = std::count_if(loop->matched_points.begin(), loop->matched_points.end(),
                                     [](const MapPointPtr& p) { return p != nullptr; });
  EXPECT_EQ(matched, loop->inliers);
  EXPECT_GT(loop->loop_points.size(), 500u);
}

TEST_F(LoopDetectorTest, InterruptedConsistencyIsRejected) {
  LoopDetector detector(recognizer_, temporal_consistency_only());
  for (int i = 0; i <= 32; ++i) ASSERT_FALSE(feed(detector, i)) << i;  // 32: first candidate
  // Keyframe 20 again: its place was visited once, so no candidate group
  // survives and the count restarts.
  EXPECT_FALSE(detector.detect(scene_.map(), *keyframes_[20]));
  EXPECT_FALSE(feed(detector, 33));
  EXPECT_FALSE(feed(detector, 34));  // only 2 consecutive now
  EXPECT_TRUE(feed(detector, 35));
}

TEST_F(LoopDetectorTest, CovisibleKeyframesConfirmTheFirstCandidate) {
  LoopDetector detector(recognizer_);
  std::optional<LoopDetection> loop;
  int found_at = -1;
  for (int i = 0; i < kKeyframes && !loop; ++i) {
    loop = feed(detector, i);
    if (loop) found_at = i;
  }
  ASSERT_TRUE(loop);
  // Keyframe 32, the first candidate: its two previous neighbours, moved by
  // the same correction, match the loop's points.
  EXPECT_EQ(found_at, 32);
  EXPECT_GE(loop->confirmations, 2);
  EXPECT_LE(loop->loop->id(), 2u);
  EXPECT_GE(loop->inliers, 100);
  const Eigen::Isometry3d truth = scene_.true_T_world_cam(found_at);
  const double corrected_error = (loop->T_world_query_corrected.translation() - truth.translation()).norm();
  const double drifted_error = (keyframes_[32]->camera_center() - truth.translation()).norm();
  std::printf("confirmed by %d neighbours, %d inliers; query position error %.3f -> %.4f m\n", loop->confirmations,
              loop->inliers, drifted_error, corrected_error);
  EXPECT_GT(drifted_error, 0.1);
  EXPECT_LT(corrected_error, 0.01);
}

TEST_F(LoopDetectorTest, UnconfirmedCandidatesWaitForTemporalConsistency) {
  LoopDetectorOptions options;
  options.min_confirmation_matches = 100000;  // no neighbour can confirm
  LoopDetector detector(recognizer_, options);
  int found_at = -1;
  for (int i = 0; i < kKeyframes && found_at < 0; ++i) {
    if (feed(detector, i)) found_at = i;
  }
  EXPECT_EQ(found_at, 34);  // as with temporal consistency only
}

TEST_F(LoopDetectorTest, CandidateGroupsMustOverlapToCount) {
  for (int i = 0; i < kKeyframes; ++i) recognizer_.add(*keyframes_[static_cast<std::size_t>(i)]);
  LoopDetectorOptions options;
  options.consistency_threshold = 2;
  LoopDetector detector(recognizer_, options);
  // Unrelated places (disjoint covisibility groups) in a row never add up.
  EXPECT_TRUE(detector.consistent_candidates({keyframes_[5]}).empty());
  EXPECT_TRUE(detector.consistent_candidates({keyframes_[20]}).empty());
  EXPECT_TRUE(detector.consistent_candidates({keyframes_[35]}).empty());
  // Overlapping groups (neighbours on the circle) do.
  const auto consistent = detector.consistent_candidates({keyframes_[36]});
  ASSERT_EQ(consistent.size(), 1u);
  EXPECT_EQ(consistent.front(), keyframes_[36]);
}

TEST_F(LoopDetectorTest, GeometricCheckRejectsAWrongPlace) {
  for (int i = 0; i < kKeyframes; ++i) recognizer_.add(*keyframes_[static_cast<std::size_t>(i)]);
  LoopDetector detector(recognizer_);
  // Keyframe 18 looks at the opposite wall of keyframe 0: nothing to align.
  EXPECT_FALSE(detector.verify(*keyframes_[37], {keyframes_[18]}));
  EXPECT_TRUE(detector.verify(*keyframes_[37], {keyframes_[1]}));
}

}  // namespace
}  // namespace stillslam
