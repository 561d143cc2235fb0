// Covisibility graph and spanning tree on a constructed map.
#include <gtest/gtest.h>

#include "map/map_builder.h"
#include "map/synthetic_scene.h"
#include "stillslam/map/map.h"

namespace stillslam {
namespace {

// Keyframes of a synthetic scene with exact data association (MapBuilder).
class GraphFixture : public ::testing::Test {
 protected:
  KeyFramePtr add_keyframe(const Eigen::Isometry3d& T_cam_world) { return builder_.add_keyframe(T_cam_world); }
  int shared_points(const KeyFrame& a, const KeyFrame& b) {
    int n = 0;
    for (const auto& mp : a.map_points()) n += (mp && mp->is_observed_by(&b)) ? 1 : 0;
    return n;
  }

  test::SyntheticScene scene_;
  test::MapBuilder builder_{scene_};
  Map& map_ = builder_.map();
};

TEST_F(GraphFixture, CovisibilityWeightsAreSharedPointCounts) {
  KeyFramePtr kf0 = add_keyframe(test::pose_at(0));
  KeyFramePtr kf1 = add_keyframe(test::pose_at(0.3));
  KeyFramePtr kf2 = add_keyframe(test::pose_at(0.6, 0, 10));
  const int w01 = shared_points(*kf0, *kf1);
  const int w12 = shared_points(*kf1, *kf2);
  const int w02 = shared_points(*kf0, *kf2);
  ASSERT_GT(w01, 100);
  EXPECT_EQ(kf0->weight(kf1.get()), w01);
  EXPECT_EQ(kf1->weight(kf0.get()), w01);
  EXPECT_EQ(kf2->weight(kf1.get()), w12);
  EXPECT_EQ(kf1->weight(kf2.get()), w12);
  EXPECT_EQ(kf2->weight(kf0.get()), w02);
  // Ordered by decreasing weight.
  const auto cov = kf1->covisibles();
  ASSERT_EQ(cov.size(), 2u);
  EXPECT_GE(kf1->weight(cov[0]), kf1->weight(cov[1]));
  EXPECT_EQ(kf1->best_covisibles(1).size(), 1u);
  EXPECT_EQ(kf1->covisibles_with_weight(std::max(w01, w12) + 1).size(), 0u);
}

TEST_F(GraphFixture, SpanningTreeParentIsStrongestFirstConnection) {
  KeyFramePtr kf0 = add_keyframe(test::pose_at(0));
  KeyFramePtr kf1 = add_keyframe(test::pose_at(0.3));
  KeyFramePtr kf2 = add_keyframe(test::pose_at(0.4));
  EXPECT_EQ(kf0->parent(), nullptr);
  EXPECT_EQ(kf1->parent(), kf0.get());
  // kf2 shares more with kf1 (closer) than with kf0.
  ASSERT_GT(shared_points(*kf2, *kf1), shared_points(*kf2, *kf0));
  EXPECT_EQ(kf2->parent(), kf1.get());
  EXPECT_EQ(kf0->children().count(kf1.get()), 1u);
  EXPECT_EQ(kf1->children().count(kf2.get()), 1u);
}

TEST_F(GraphFixture, CullingKeyFrameReparentsChildrenAndDropsEdges) {
  KeyFramePtr kf0 = add_keyframe(test::pose_at(0));
  KeyFramePtr kf1 = add_keyframe(test::pose_at(0.3));
  KeyFramePtr kf2 = add_keyframe(test::pose_at(0.4));
  KeyFramePtr kf3 = add_keyframe(test::pose_at(0.5));
  ASSERT_EQ(kf2->parent(), kf1.get());
  const Eigen::Isometry3d T_before = kf1->T_cam_world();
  const std::size_t points_before = map_.num_map_points();
  map_.erase_keyframe(kf1);
  EXPECT_TRUE(kf1->is_bad());
  EXPECT_EQ(map_.num_keyframes(), 3u);
  EXPECT_EQ(kf0->weight(kf1.get()), 0);
  EXPECT_EQ(kf2->weight(kf1.get()), 0);
  // kf2 now hangs from a keyframe that was in the candidate set (kf0).
  EXPECT_EQ(kf2->parent(), kf0.get());
  EXPECT_EQ(kf0->children().count(kf1.get()), 0u);
  // No map point still lists kf1; points seen by kf1 only became bad.
  for (const auto& mp : map_.map_points()) EXPECT_FALSE(mp->is_observed_by(kf1.get()));
  EXPECT_LE(map_.num_map_points(), points_before);
  // The culled keyframe's pose is still available through its parent.
  EXPECT_LT((kf1->T_cam_world_resolved().matrix() - T_before.matrix()).norm(), 1e-9);
  // The first keyframe is never culled.
  map_.erase_keyframe(kf0);
  EXPECT_FALSE(kf0->is_bad());
}

TEST_F(GraphFixture, MapPointDescriptorAndScaleRange) {
  KeyFramePtr kf0 = add_keyframe(test::pose_at(0));
  KeyFramePtr kf1 = add_keyframe(test::pose_at(0.2));
  const MapPointPtr& mp = kf0->map_point(0);
  ASSERT_TRUE(mp);
  // Identical descriptors in every view: the representative equals them.
  EXPECT_EQ(std::memcmp(mp->descriptor(), kf0->descriptor(0), 32), 0);
  const double d = (mp->position() - kf0->camera_center()).norm();
  // Seen at level 0 from the reference: predicted level 0 at that distance,
  // higher levels closer.
  EXPECT_EQ(mp->predict_level(d, scene_.setup()->pyramid), 0);
  EXPECT_EQ(mp->predict_level(d / 1.2 / 1.2, scene_.setup()->pyramid), 2);
  EXPECT_LT(mp->min_distance(), d);
  EXPECT_GT(mp->max_distance(), d);
  EXPECT_NEAR(mp->normal().norm(), 1.0, 1e-12);
}

}  // namespace
}  // namespace stillslam
