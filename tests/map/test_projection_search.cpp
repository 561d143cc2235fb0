// Guided matching by projection on a synthetic scene (ground-truth identities).
#include <gtest/gtest.h>

#include "map/synthetic_scene.h"
#include "stillslam/map/fuse.h"
#include "stillslam/map/map.h"
#include "stillslam/map/projection_search.h"
#include "stillslam/map/triangulation_search.h"

namespace stillslam {
namespace {

struct Fixture {
  test::SyntheticScene scene;
  Map map;
  std::vector<std::size_t> ids0;
  Frame frame0;
  KeyFramePtr kf0;
  std::map<const MapPoint*, std::size_t> scene_index;

  Fixture() {
    frame0 = scene.make_frame(0, test::pose_at(0), &ids0);
    frame0.set_pose(test::pose_at(0));
    kf0 = map.create_keyframe(frame0);
    for (std::size_t i = 0; i < ids0.size(); ++i) {
      MapPointPtr mp = map.create_map_point(scene.points()[ids0[i]], kf0.get());
      mp->add_observation(kf0.get(), i);
      kf0->set_map_point(i, mp);
      mp->compute_distinctive_descriptor();
      mp->update_normal_and_depth(scene.setup()->pyramid);
      frame0.set_map_point(i, mp);
      scene_index[mp.get()] = ids0[i];
    }
  }
};

TEST(ProjectionSearch, MotionModelMatchesLastFrameWithPerturbedPose) {
  Fixture f;
  std::vector<std::size_t> ids1;
  const Eigen::Isometry3d T1 = test::pose_at(0.15, 0.02, 3);
  Frame frame1 = f.scene.make_frame(1, T1, &ids1);
  // Prediction off by ~1 cm and ~0.3 degrees.
  Eigen::Isometry3d predicted = T1;
  predicted.pretranslate(Eigen::Vector3d(0.01, -0.005, 0.0));
  predicted.rotate(Eigen::AngleAxisd(0.005, Eigen::Vector3d::UnitX()));
  frame1.set_pose(predicted);
  const int n = search_by_projection(frame1, f.frame0, 7.f);
  int correct = 0, common = 0;
  std::set<std::size_t> seen0(f.ids0.begin(), f.ids0.end());
  for (std::size_t i = 0; i < frame1.size(); ++i) {
    common += seen0.count(ids1[i]) ? 1 : 0;
    const MapPointPtr& mp = frame1.map_point(i);
    if (mp) correct += f.scene_index.at(mp.get()) == ids1[i] ? 1 : 0;
  }
  ASSERT_GT(common, 300);
  EXPECT_EQ(n, frame1.num_matches());
  EXPECT_GT(n, 0.95 * common);
  EXPECT_EQ(correct, n);
}

TEST(ProjectionSearch, LocalPointsInFrustumAreMatched) {
  Fixture f;
  std::vector<std::size_t> ids1;
  const Eigen::Isometry3d T1 = test::pose_at(0.3, 0.0, -5);
  Frame frame1 = f.scene.make_frame(1, T1, &ids1);
  frame1.set_pose(T1);
  std::vector<ProjectedPoint> projected;
  int outside = 0;
  for (const auto& mp : f.map.map_points()) {
    auto p = project_in_frustum(frame1, mp);
    if (p) {
      projected.push_back(*p);
      EXPECT_LE(p->level, 1);  // keypoints are at level 0; ceil() may predict 1 when closer
    } else {
      ++outside;
    }
  }
  ASSERT_GT(projected.size(), 300u);
  EXPECT_GT(outside, 0);  // the camera turned: some points left the image
  const int n = search_by_projection(frame1, projected, 3.f);
  int correct = 0;
  for (std::size_t i = 0; i < frame1.size(); ++i) {
    const MapPointPtr& mp = frame1.map_point(i);
    if (mp) correct += f.scene_index.at(mp.get()) == ids1[i] ? 1 : 0;
  }
  EXPECT_GT(n, 0.95 * static_cast<double>(projected.size()));
  EXPECT_EQ(correct, n);
}

TEST(ProjectionSearch, TriangulationSearchFindsEpipolarMatches) {
  Fixture f;
  std::vector<std::size_t> ids1;
  const Eigen::Isometry3d T1 = test::pose_at(0.3);
  Frame frame1 = f.scene.make_frame(1, T1, &ids1);
  frame1.set_pose(T1);
  KeyFramePtr kf1 = f.map.create_keyframe(frame1);
  // kf0 has every slot matched: clear half of them to leave work for the search.
  for (std::size_t i = 0; i < f.kf0->size(); i += 2) f.kf0->erase_map_point(i);
  const auto matches = search_for_triangulation(*f.kf0, *kf1);
  std::size_t correct = 0;
  for (const auto& [i0, i1] : matches) correct += f.ids0[i0] == ids1[i1] ? 1 : 0;
  std::set<std::size_t> seen1(ids1.begin(), ids1.end());
  std::size_t possible = 0;
  for (std::size_t i = 0; i < f.kf0->size(); i += 2) possible += seen1.count(f.ids0[i]);
  ASSERT_GT(possible, 200u);
  EXPECT_GT(matches.size(), 0.9 * static_cast<double>(possible));
  EXPECT_EQ(correct, matches.size());
}

TEST(ProjectionSearch, FuseMergesDuplicatePoints) {
  Fixture f;
  std::vector<std::size_t> ids1;
  const Eigen::Isometry3d T1 = test::pose_at(0.2);
  Frame frame1 = f.scene.make_frame(1, T1, &ids1);
  frame1.set_pose(T1);
  KeyFramePtr kf1 = f.map.create_keyframe(frame1);
  // kf1 gets its own duplicate points for everything it sees.
  std::vector<MapPointPtr> duplicates;
  for (std::size_t i = 0; i < kf1->size(); ++i) {
    MapPointPtr mp = f.map.create_map_point(*kf1->unproject(i), kf1.get());
    mp->add_observation(kf1.get(), i);
    kf1->set_map_point(i, mp);
    mp->compute_distinctive_descriptor();
    mp->update_normal_and_depth(f.scene.setup()->pyramid);
    duplicates.push_back(mp);
  }
  const std::size_t before = f.map.num_map_points();
  const int fused = fuse(*kf1, f.map.map_points());
  f.map.remove_bad_points();
  std::set<std::size_t> seen0(f.ids0.begin(), f.ids0.end());
  std::size_t common = 0;
  for (std::size_t id : ids1) common += seen0.count(id);
  EXPECT_GT(fused, 0.95 * static_cast<double>(common));
  EXPECT_EQ(f.map.num_map_points(), before - static_cast<std::size_t>(fused));
  // Every surviving slot of kf1 points at a point seen by both keyframes where possible.
  std::size_t shared = 0;
  for (const auto& mp : kf1->map_points()) shared += (mp && mp->is_observed_by(f.kf0.get())) ? 1 : 0;
  EXPECT_EQ(shared, static_cast<std::size_t>(fused));
}

}  // namespace
}  // namespace stillslam
