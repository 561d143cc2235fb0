// Redundant keyframe culling rule on constructed maps.
#include <gtest/gtest.h>

#include "map/map_builder.h"
#include "stillslam/mapping/keyframe_culling.h"

namespace stillslam {
namespace {

TEST(KeyFrameCulling, KeyFramesSeenByThreeOthersAreCulledInOrder) {
  test::SyntheticScene scene;
  test::MapBuilder builder(scene);
  std::vector<KeyFramePtr> kfs;
  for (int k = 0; k < 5; ++k) kfs.push_back(builder.add_keyframe(test::pose_at(0.01 * k)));
  // Every close point of kf1 is seen by 4 other keyframes at the same level.
  EXPECT_DOUBLE_EQ(keyframe_redundancy(*kfs[1]), 1.0);
  std::vector<std::uint64_t> culled_ids;
  const int culled = cull_redundant_keyframes(builder.map(), *kfs[4], {}, &culled_ids);
  // kf0 is never culled. Two of kf1..kf3 go (in covisibility order); then the
  // survivor's points have only kf0 and kf4 as other observers (< 3): it stays.
  EXPECT_EQ(culled, 2);
  ASSERT_EQ(culled_ids.size(), 2u);
  for (std::uint64_t id : culled_ids) EXPECT_TRUE(builder.map().keyframe(id) == nullptr) << id;
  EXPECT_FALSE(kfs[0]->is_bad());
  EXPECT_FALSE(kfs[4]->is_bad());
  int survivors = 0;
  for (int k = 1; k <= 3; ++k) {
    if (kfs[k]->is_bad()) continue;
    ++survivors;
    EXPECT_LT(keyframe_redundancy(*kfs[k]), 0.9);
  }
  EXPECT_EQ(survivors, 1);
  EXPECT_EQ(builder.map().num_keyframes(), 3u);
}

TEST(KeyFrameCulling, KeyFrameWithOwnStructureIsKept) {
  test::SyntheticScene scene;
  test::MapBuilder builder(scene);
  KeyFramePtr a = builder.add_keyframe(test::pose_at(0));
  KeyFramePtr b = builder.add_keyframe(test::pose_at(0.02));
  KeyFramePtr c = builder.add_keyframe(test::pose_at(0.04));
  // Turned well away: most of its points are new (seen by nobody else).
  KeyFramePtr d = builder.add_keyframe(test::pose_at(0.06, 0, 25));
  KeyFramePtr e = builder.add_keyframe(test::pose_at(0.08));
  const double r = keyframe_redundancy(*d);
  EXPECT_LT(r, 0.9);
  EXPECT_GT(r, 0.0);
  cull_redundant_keyframes(builder.map(), *e);
  EXPECT_FALSE(d->is_bad());
  EXPECT_FALSE(a->is_bad());
}

TEST(KeyFrameCulling, FarPointsDoNotCount) {
  test::SyntheticScene scene;
  test::MapBuilder builder(scene);
  KeyFramePtr kf = builder.add_keyframe(test::pose_at(0));
  int close = 0, total = 0;
  for (std::size_t i = 0; i < kf->size(); ++i) {
    ++total;
    close += kf->depth(i) <= kf->setup().close_depth ? 1 : 0;
  }
  ASSERT_GT(close, 0);
  ASSERT_LT(close, total);
  // A single keyframe: nothing is redundant.
  EXPECT_DOUBLE_EQ(keyframe_redundancy(*kf), 0.0);
}

}  // namespace
}  // namespace stillslam
