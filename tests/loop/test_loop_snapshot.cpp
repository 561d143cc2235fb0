// Loop detection in three steps (prepare under the map lock, verify on the
// snapshot without it, recheck under it again) on the synthetic circle of
// loop_scene.h: verify gives exactly detect()'s detection even when the map
// moves between prepare and verify, and recheck rejects what changed meanwhile.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <functional>
#include <mutex>
#include <thread>

#include "loop/loop_scene.h"
#include "stillslam/loop/loop_detector.h"

namespace stillslam {
namespace {

constexpr int kKeyframes = 42;

class LoopSnapshotTest : public ::testing::Test {
 protected:
  LoopSnapshotTest() : recognizer_(std::make_shared<const Vocabulary>(scene_.train_vocabulary())) {
    for (int i = 0; i < kKeyframes; ++i) keyframes_.push_back(scene_.add_keyframe(i));
  }
  const KeyFramePtr& kf(int i) const { return keyframes_[static_cast<std::size_t>(i)]; }

  // Feeds keyframes 0, 1, ... to `detector` in three steps until it verifies
  // a loop; returns it and the keyframe it was found at.
  std::pair<std::optional<LoopDetection>, int> first_verified(LoopDetector& detector) {
    for (int i = 0; i < kKeyframes; ++i) {
      std::optional<LoopSnapshot> s = detector.prepare(scene_.map(), *kf(i));
      std::optional<LoopDetection> d = s ? detector.verify(*s) : std::nullopt;
      recognizer_.add(*kf(i));
      if (d) return {d, i};
    }
    return {std::nullopt, -1};
  }

  // Moves every keyframe and point (as a local BA would) and returns a
  // function that puts them back bit for bit.
  std::function<void()> disturb_map() {
    std::vector<std::pair<KeyFramePtr, Eigen::Isometry3d>> poses;
    std::vector<std::pair<MapPointPtr, Eigen::Vector3d>> positions;
    Eigen::Isometry3d shift = Eigen::Isometry3d::Identity();
    shift.translation() = Eigen::Vector3d(0.3, -0.2, 0.1);
    for (const auto& k : scene_.map().keyframes()) {
      poses.emplace_back(k, k->T_cam_world());
      k->set_pose(k->T_cam_world() * shift);
    }
    for (const auto& p : scene_.map().map_points()) {
      positions.emplace_back(p, p->position());
      p->set_position(p->position() + Eigen::Vector3d(0.3, -0.2, 0.1));
    }
    return [poses, positions] {
      for (const auto& [k, T] : poses) k->set_pose(T);
      for (const auto& [p, x] : positions) p->set_position(x);
    };
  }

  test::LoopScene scene_;
  PlaceRecognizer recognizer_;
  std::vector<KeyFramePtr> keyframes_;
};

void expect_same(const LoopDetection& a, const LoopDetection& b) {
  EXPECT_EQ(a.query, b.query);
  EXPECT_EQ(a.loop, b.loop);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.confirmations, b.confirmations);
  EXPECT_TRUE(a.T_world_query_corrected.matrix() == b.T_world_query_corrected.matrix())
      << a.T_world_query_corrected.matrix() << "\nvs\n" << b.T_world_query_corrected.matrix();
  EXPECT_TRUE(a.matched_points == b.matched_points);
  EXPECT_TRUE(a.loop_points == b.loop_points);
}

// detect() and prepare + verify side by side on two detectors (each keeps its
// own consistency state), with the map moved between prepare and verify.
class LoopSnapshotSideBySide : public LoopSnapshotTest {
 protected:
  void run(const LoopDetectorOptions& options, int expected_at, bool confirmed) {
    LoopDetector reference(recognizer_, options), stepwise(recognizer_, options);
    int found_at = -1;
    for (int i = 0; i < kKeyframes && found_at < 0; ++i) {
      const std::optional<LoopDetection> expected = reference.detect(scene_.map(), *kf(i));
      const std::optional<LoopSnapshot> snapshot = stepwise.prepare(scene_.map(), *kf(i));
      const std::function<void()> restore = disturb_map();
      const std::optional<LoopDetection> got = snapshot ? stepwise.verify(*snapshot) : std::nullopt;
      restore();
      recognizer_.add(*kf(i));
      ASSERT_EQ(expected.has_value(), got.has_value()) << "keyframe " << i;
      if (!expected) continue;
      found_at = i;
      expect_same(*expected, *got);
      EXPECT_EQ(confirmed, got->confirmations > 0);
      const std::optional<LoopDetection> rechecked = stepwise.recheck(scene_.map(), *got);
      ASSERT_TRUE(rechecked);
      expect_same(*expected, *rechecked);
    }
    EXPECT_EQ(found_at, expected_at);
  }
};

TEST_F(LoopSnapshotSideBySide, CovisibleConfirmationGivesDetectsDetection) {
  run(LoopDetectorOptions{}, 32, true);
}

TEST_F(LoopSnapshotSideBySide, TemporalConsistencyGivesDetectsDetection) {
  LoopDetectorOptions options;
  options.confirmation_neighbours = 0;
  run(options, 34, false);
}

// As the loop closer will run it: verify() on another thread while this one
// keeps moving the map under the lock (a ThreadSanitizer build reports any
// read of live map state); the detection is the one detect() found before.
TEST_F(LoopSnapshotTest, VerifyOnAnotherThreadWhileTheMapChanges) {
  LoopDetector reference(recognizer_), stepwise(recognizer_);
  std::optional<LoopDetection> expected;
  std::optional<LoopSnapshot> snapshot;
  int i = 0;
  for (; i < kKeyframes && !expected; ++i) {
    expected = reference.detect(scene_.map(), *kf(i));
    snapshot = stepwise.prepare(scene_.map(), *kf(i));
    if (!expected) recognizer_.add(*kf(i));
  }
  ASSERT_TRUE(expected && snapshot);
  std::atomic<bool> done{false};
  std::optional<LoopDetection> got;
  std::thread verifier([&] {
    got = stepwise.verify(*snapshot);
    done = true;
  });
  int rounds = 0;
  for (; !done || rounds == 0; ++rounds) {
    std::lock_guard<std::mutex> lock(scene_.map().update_mutex());
    disturb_map()();  // moves everything and back
  }
  verifier.join();
  ASSERT_TRUE(got);
  expect_same(*expected, *got);
  std::lock_guard<std::mutex> lock(scene_.map().update_mutex());
  const auto rechecked = stepwise.recheck(scene_.map(), *got);
  ASSERT_TRUE(rechecked);
  expect_same(*expected, *rechecked);
}

TEST_F(LoopSnapshotTest, SnapshotHoldsTheCandidatesToVerify) {
  LoopDetector detector(recognizer_);
  for (int i = 0; i < 32; ++i) {
    detector.prepare(scene_.map(), *kf(i));
    recognizer_.add(*kf(i));
  }
  const std::optional<LoopSnapshot> s = detector.prepare(scene_.map(), *kf(32));
  ASSERT_TRUE(s);
  ASSERT_FALSE(s->candidates.empty());
  EXPECT_EQ(s->query.keyframe, kf(32));
  EXPECT_TRUE(s->candidates.front().needs_confirmation);  // the first candidate is not consistent yet
  EXPECT_EQ(s->candidates.front().needed_confirmations, 2);
  EXPECT_FALSE(s->neighbours.empty());
  // Copies, not references: moving a loop point after prepare leaves the snapshot as it was.
  const LoopCandidateCopy& c = s->candidates.front();
  const PointCopy& p = s->points[static_cast<std::size_t>(c.loop_points.front())];
  const Eigen::Vector3d before = p.position;
  p.point->set_position(before + Eigen::Vector3d::Ones());
  EXPECT_TRUE(p.position == before);
}

class LoopRecheckTest : public LoopSnapshotTest {
 protected:
  LoopDetection verified() {
    LoopDetector detector(recognizer_);
    auto [d, at] = first_verified(detector);
    EXPECT_EQ(at, 32);
    EXPECT_TRUE(d);
    return d ? *d : LoopDetection{};
  }
};

TEST_F(LoopRecheckTest, AcceptsAnUnchangedDetection) {
  const LoopDetection d = verified();
  LoopDetector detector(recognizer_);
  const auto r = detector.recheck(scene_.map(), d);
  ASSERT_TRUE(r);
  expect_same(d, *r);
}

TEST_F(LoopSnapshotTest, RecheckRejectsALoopKeyframeCulledAfterPrepare) {
  // The detector finds keyframe 0, the map's origin, which is never culled:
  // snapshot keyframe 37 against keyframe 1 (the same place) directly.
  for (const auto& k : keyframes_) recognizer_.add(*k);
  LoopDetector detector(recognizer_);
  LoopSnapshotBuilder builder(*kf(37), recognizer_.description(37), 0);
  builder.add_candidate(kf(1), recognizer_.description(1));
  const LoopSnapshot snapshot = builder.take();
  scene_.map().erase_keyframe(kf(1));  // local mapping culls it while verify runs
  ASSERT_TRUE(kf(1)->is_bad());
  const std::optional<LoopDetection> d = detector.verify(snapshot);  // the snapshot still has it
  ASSERT_TRUE(d);
  EXPECT_EQ(d->loop, kf(1));
  EXPECT_GE(d->inliers, 100);
  EXPECT_FALSE(detector.recheck(scene_.map(), *d));
}

TEST_F(LoopRecheckTest, RejectsAQueryCulledMeanwhile) {
  LoopDetection d = verified();
  LoopDetector detector(recognizer_);
  scene_.map().erase_keyframe(d.query);
  EXPECT_FALSE(detector.recheck(scene_.map(), d));
}

TEST_F(LoopRecheckTest, DropsMatchedPointsTurnedBadAndRejectsBelowMinInliers) {
  const LoopDetection d = verified();
  LoopDetectorOptions options;
  LoopDetector detector(recognizer_, options);
  std::vector<MapPointPtr> matched;
  for (const auto& mp : d.matched_points) {
    if (mp) matched.push_back(mp);
  }
  ASSERT_EQ(static_cast<int>(matched.size()), d.inliers);
  ASSERT_GT(d.inliers, options.min_inliers + 10);
  // Culled points down to exactly min_inliers: accepted with the rest.
  const std::size_t cull = matched.size() - static_cast<std::size_t>(options.min_inliers);
  for (std::size_t k = 0; k < cull; ++k) matched[k]->set_bad();
  const auto kept = detector.recheck(scene_.map(), d);
  ASSERT_TRUE(kept);
  EXPECT_EQ(kept->inliers, options.min_inliers);
  for (std::size_t k = 0; k < cull; ++k) {
    EXPECT_EQ(std::count(kept->matched_points.begin(), kept->matched_points.end(), matched[k]), 0);
    EXPECT_EQ(std::count(kept->loop_points.begin(), kept->loop_points.end(), matched[k]), 0);
  }
  EXPECT_EQ(kept->loop_points.size(), d.loop_points.size() - cull);
  // One more: below min_inliers.
  matched[cull]->set_bad();
  EXPECT_FALSE(detector.recheck(scene_.map(), d));
}

}  // namespace
}  // namespace stillslam
