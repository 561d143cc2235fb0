// Map merging on a synthetic scene with a known answer: map A (degrees 0-150
// of a circle) and map B (110-270) built independently, B in an unknown frame.
// The merge detector finds B's start in A after 3 consistent keyframes, the
// merger moves B into A's frame: every keyframe and point then agrees with the
// truth, duplicates are fused, and the maps form one spanning tree.
#include <gtest/gtest.h>

#include <unordered_set>

#include "loop/map_merge_scene.h"
#include "stillslam/loop/map_merger.h"
#include "stillslam/loop/merge_detector.h"

namespace stillslam {
namespace {

using Scene = test::MapMergeScene;

Eigen::Isometry3d unknown_transform() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(35.0 * M_PI / 180.0, Eigen::Vector3d(0.3, 1.0, 0.2).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(1.5, -0.4, 2.0);
  return T;
}

class MapMergerTest : public ::testing::Test {
 protected:
  MapMergerTest()
      : ids_(std::make_shared<MapIdCounters>()),
        a_(0, ids_),
        b_(1, ids_),
        recognizer_(std::make_shared<const Vocabulary>(scene_.train_vocabulary())) {
    build_a_.map = &a_;
    build_b_.map = &b_;
    build_b_.T_map_world = unknown_transform();
    for (double deg = 0; deg <= 150; deg += 10) recognizer_.add(*scene_.add_keyframe(build_a_, deg));
  }

  // Adds B's keyframes from `from_deg` on until the detector fires (then
  // returns the detection and how many keyframes it took) or `to_deg`.
  std::pair<std::optional<LoopDetection>, int> build_b_until_detected(MergeDetector& detector, double from_deg,
                                                                       double to_deg) {
    int n = 0;
    for (double deg = from_deg; deg <= to_deg; deg += 10) {
      KeyFramePtr kf = scene_.add_keyframe(build_b_, deg);
      ++n;
      auto d = detector.detect(a_, *kf);
      recognizer_.add(*kf);
      if (d) return {d, n};
    }
    return {std::nullopt, n};
  }

  // Largest camera-centre / rotation error of a map's keyframes against the truth.
  std::pair<double, double> max_errors(const Map& map) const {
    double position = 0, rotation = 0;
    for (const KeyFramePtr& kf : map.keyframes()) {
      const auto it_a = build_a_.degrees.find(kf->id());
      const double deg = it_a != build_a_.degrees.end() ? it_a->second : build_b_.degrees.at(kf->id());
      const Eigen::Isometry3d truth = Scene::true_T_world_cam(deg);
      position = std::max(position, (kf->camera_center() - truth.translation()).norm());
      const Eigen::Matrix3d dR = kf->T_world_cam().linear().transpose() * truth.linear();
      rotation = std::max(rotation, Eigen::AngleAxisd(dR).angle() * 180.0 / M_PI);
    }
    return {position, rotation};
  }

  Scene scene_;
  std::shared_ptr<MapIdCounters> ids_;
  Map a_, b_;
  Scene::MapBuild build_a_, build_b_;
  PlaceRecognizer recognizer_;
};

TEST_F(MapMergerTest, IdsAreUniqueAcrossMapsSharingCounters) {
  scene_.add_keyframe(build_b_, 110);
  std::unordered_set<std::uint64_t> keyframe_ids, point_ids;
  for (const Map* m : {&a_, &b_}) {
    for (const auto& kf : m->keyframes()) EXPECT_TRUE(keyframe_ids.insert(kf->id()).second) << kf->id();
    for (const auto& mp : m->map_points()) EXPECT_TRUE(point_ids.insert(mp->id()).second) << mp->id();
  }
  EXPECT_EQ(keyframe_ids.size(), 17u);
  // Each map's first keyframe is its origin (B's has id 16, not 0).
  EXPECT_TRUE(a_.keyframes().front()->is_origin());
  EXPECT_TRUE(b_.keyframes().front()->is_origin());
  EXPECT_EQ(b_.keyframes().front()->id(), 16u);
  EXPECT_FALSE(a_.keyframes()[1]->is_origin());
}

TEST_F(MapMergerTest, DetectsAfterThreeConsistentKeyframesAndMergesOntoTheTruth) {
  MergeDetector detector(recognizer_);
  auto [detection, used] = build_b_until_detected(detector, 110, 270);
  ASSERT_TRUE(detection);
  EXPECT_EQ(used, 3);  // 110, 120, 130: three consistent keyframes
  EXPECT_GE(detection->inliers, 200);
  EXPECT_TRUE(a_.keyframe(detection->loop->id()));
  EXPECT_TRUE(b_.keyframe(detection->query->id()));
  // The rest of B (up to 270 degrees, far beyond A).
  for (double deg = 140; deg <= 270; deg += 10) scene_.add_keyframe(build_b_, deg);
  const std::size_t keyframes_b = b_.num_keyframes();
  EXPECT_GT(max_errors(b_).first, 1.0);  // B is in its own frame before the merge

  const MapMergeStats stats = merge_maps(a_, b_, *detection);
  std::cout << "merge: " << stats.moved_keyframes << " keyframes, " << stats.moved_points << " points moved, "
            << stats.fused_points << " fused, welding window " << stats.welding_keyframes << " free / "
            << stats.welding_fixed_keyframes << " fixed, " << stats.welding_outliers << " outliers, graph "
            << stats.graph_nodes << " nodes " << stats.graph_edges << " edges\n";
  // The transform found is the unknown one (A's world = true world).
  const Eigen::Isometry3d dT = stats.T_target_source * unknown_transform();
  EXPECT_LT(dT.translation().norm(), 0.005);
  EXPECT_LT(Eigen::AngleAxisd(dT.linear()).angle() * 180.0 / M_PI, 0.1);

  EXPECT_TRUE(b_.empty());
  EXPECT_EQ(a_.num_keyframes(), 16u + keyframes_b);
  const auto [position, rotation] = max_errors(a_);
  std::cout << "after merge: max keyframe error " << position * 1000 << " mm, " << rotation << " deg\n";
  EXPECT_LT(position, 0.01);
  EXPECT_LT(rotation, 0.2);

  // Points: B's points (followed through fusion) sit on the true scene points.
  double max_point_error = 0;
  int checked = 0;
  for (const auto& [s, entry] : build_b_.live) {
    MapPointPtr mp = entry.first;
    while (mp && mp->is_bad() && mp->replaced_by()) mp = mp->replaced_by();
    if (!mp || mp->is_bad()) continue;
    max_point_error = std::max(max_point_error, (mp->position() - scene_.point(s)).norm());
    ++checked;
  }
  EXPECT_GT(checked, 500);
  EXPECT_LT(max_point_error, 0.02);

  // Fusion joined the seam: the overlap's points are shared, B's query sees A's keyframes.
  EXPECT_GT(stats.fused_points, 200);
  bool linked = false;
  for (KeyFrame* n : detection->query->covisibles()) linked = linked || build_a_.degrees.count(n->id()) > 0;
  EXPECT_TRUE(linked);

  // One spanning tree rooted at A's origin; B's old origin is an ordinary keyframe.
  int roots = 0, origins = 0;
  for (const KeyFramePtr& kf : a_.keyframes()) {
    roots += kf->parent() == nullptr ? 1 : 0;
    origins += kf->is_origin() ? 1 : 0;
    int steps = 0;
    for (KeyFrame* k = kf.get(); k->parent() != nullptr && steps < 100; k = k->parent()) ++steps;
    EXPECT_LT(steps, 100) << "cycle above keyframe " << kf->id();
  }
  EXPECT_EQ(roots, 1);
  EXPECT_EQ(origins, 1);
  EXPECT_EQ(detection->query->parent(), detection->loop.get());
}

TEST_F(MapMergerTest, NoDetectionWhereTheOtherMapHasNotBeen) {
  MergeDetector detector(recognizer_);
  // 230-330 degrees: the camera looks at wall A never saw (A looked at 0-150 +- 33).
  auto [detection, used] = build_b_until_detected(detector, 230, 330);
  EXPECT_FALSE(detection);
  EXPECT_EQ(used, 11);
}

}  // namespace
}  // namespace stillslam
