// Atlas: maps with unique ids, one active map, keyframe/point ids unique
// across maps (shared counters), each map's first keyframe its origin, maps
// emptied by a merge removed, keyframes found by map.
#include <gtest/gtest.h>

#include <unordered_set>

#include "map/synthetic_scene.h"
#include "stillslam/core/error.h"
#include "stillslam/map/atlas.h"
#include "stillslam/map/frame.h"

namespace stillslam {
namespace {

KeyFramePtr add_keyframe(Map& map, const test::SyntheticScene& scene, std::uint64_t frame_id, double x) {
  Eigen::Isometry3d T_cam_world = Eigen::Isometry3d::Identity();
  T_cam_world.translation() = Eigen::Vector3d(x, 0, 0);
  Frame frame = scene.make_frame(frame_id, T_cam_world, nullptr);
  frame.set_pose(T_cam_world);
  KeyFramePtr kf = map.create_keyframe(frame);
  for (int i = 0; i < 3; ++i) map.create_map_point(Eigen::Vector3d(x, i, 5), kf.get());
  return kf;
}

TEST(Atlas, StartsWithOneActiveMapAndCreatesMore) {
  Atlas atlas;
  EXPECT_EQ(atlas.num_maps(), 1u);
  EXPECT_EQ(atlas.active_map_id(), 0u);
  EXPECT_EQ(&atlas.active_map(), atlas.map(0));
  Map& second = atlas.create_map();
  EXPECT_EQ(second.id(), 1u);
  EXPECT_EQ(atlas.active_map_id(), 1u);
  EXPECT_EQ(atlas.num_maps(), 2u);
  EXPECT_EQ(atlas.maps_created(), 2u);
  atlas.set_active_map(0);
  EXPECT_EQ(&atlas.active_map(), atlas.map(0));
  EXPECT_THROW(atlas.set_active_map(7), Error);
  EXPECT_EQ(atlas.map(7), nullptr);
  ASSERT_EQ(atlas.maps().size(), 2u);
  EXPECT_EQ(atlas.maps()[1], &second);
}

TEST(Atlas, IdsAreUniqueAcrossMapsAndEachMapHasItsOrigin) {
  const test::SyntheticScene scene;
  Atlas atlas;
  Map& first = atlas.active_map();
  std::vector<KeyFramePtr> kfs;
  kfs.push_back(add_keyframe(first, scene, 0, 0.0));
  kfs.push_back(add_keyframe(first, scene, 1, 0.1));
  Map& second = atlas.create_map();
  kfs.push_back(add_keyframe(second, scene, 2, 0.2));
  kfs.push_back(add_keyframe(second, scene, 3, 0.3));
  EXPECT_EQ(kfs[2]->id(), 2u);  // continues the first map's ids
  EXPECT_TRUE(kfs[0]->is_origin());
  EXPECT_FALSE(kfs[1]->is_origin());
  EXPECT_TRUE(kfs[2]->is_origin());  // id 2, but the second map's first keyframe
  EXPECT_FALSE(kfs[3]->is_origin());
  std::unordered_set<std::uint64_t> points;
  for (Map* m : atlas.maps()) {
    for (const auto& mp : m->map_points()) EXPECT_TRUE(points.insert(mp->id()).second);
  }
  EXPECT_EQ(points.size(), 12u);
  EXPECT_EQ(atlas.map_of_keyframe(1), 0u);
  EXPECT_EQ(atlas.map_of_keyframe(3), 1u);
  EXPECT_FALSE(atlas.map_of_keyframe(4).has_value());
  EXPECT_EQ(first.keyframe(2), nullptr);  // a map only knows its own keyframes
}

TEST(Atlas, AbsorbedMapIsRemovedAndItsKeyframesFoundInTheTarget) {
  const test::SyntheticScene scene;
  Atlas atlas;
  Map& first = atlas.active_map();
  add_keyframe(first, scene, 0, 0.0);
  Map& second = atlas.create_map();
  add_keyframe(second, scene, 1, 0.1);
  KeyFramePtr kf = add_keyframe(second, scene, 2, 0.2);
  EXPECT_THROW(atlas.remove_map(1), Error);  // active
  atlas.set_active_map(0);
  EXPECT_THROW(atlas.remove_map(1), Error);  // not empty
  first.absorb(second);
  EXPECT_TRUE(second.empty());
  EXPECT_EQ(first.num_keyframes(), 3u);
  EXPECT_EQ(first.num_map_points(), 9u);
  EXPECT_EQ(first.keyframe(2), kf);
  ASSERT_EQ(first.all_keyframes().size(), 3u);
  EXPECT_EQ(first.all_keyframes()[2], kf);  // by id
  atlas.remove_map(1);
  EXPECT_EQ(atlas.num_maps(), 1u);
  EXPECT_EQ(atlas.map_of_keyframe(2), 0u);
  // New maps never reuse an id.
  EXPECT_EQ(atlas.create_map().id(), 2u);
}

TEST(Atlas, AddsLoadedMapsKeepingTheirIds) {
  Atlas atlas;
  auto loaded = std::make_unique<Map>(5, atlas.id_counters());
  atlas.add_map(std::move(loaded));
  EXPECT_EQ(atlas.num_maps(), 2u);
  EXPECT_NE(atlas.map(5), nullptr);
  EXPECT_THROW(atlas.add_map(std::make_unique<Map>(5, atlas.id_counters())), Error);
  EXPECT_EQ(atlas.create_map().id(), 6u);
}

}  // namespace
}  // namespace stillslam
