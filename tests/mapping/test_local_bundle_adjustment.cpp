// Local BA window around a keyframe: composition, noise reduction, outlier removal.
#include <gtest/gtest.h>

#include <random>

#include "map/map_builder.h"
#include "stillslam/mapping/local_bundle_adjustment.h"
#include "stillslam/mapping/local_mapper.h"
#include "stillslam/mapping/point_culling.h"

namespace stillslam {
namespace {

TEST(LocalBundleAdjustment, WindowHasCovisiblesAndFixedObservers) {
  test::SyntheticScene scene;
  test::MapBuilder builder(scene);
  std::vector<KeyFramePtr> kfs;
  for (int k = 0; k < 4; ++k) kfs.push_back(builder.add_keyframe(test::pose_at(0.1 * k)));
  const LocalBundleAdjustmentProblem p = gather_local_window(*kfs[3]);
  // kf3 and its covisibles (all others) are local; kf0 fixed as gauge anchor.
  ASSERT_EQ(p.keyframes.size(), 4u);
  EXPECT_EQ(p.keyframes[0], kfs[3]);
  int fixed = 0;
  for (const auto& k : p.ba_keyframes) fixed += k.fixed ? 1 : 0;
  EXPECT_EQ(fixed, 1);
  EXPECT_EQ(p.points.size(), builder.map().num_map_points());
  std::size_t observations = 0;
  for (const auto& mp : p.points) observations += mp->observations().size();
  EXPECT_EQ(p.ba_observations.size(), observations);
}

TEST(LocalBundleAdjustment, WindowStaysWithinItsBudget) {
  test::SyntheticScene scene;
  test::MapBuilder builder(scene);
  std::vector<KeyFramePtr> kfs;
  for (int k = 0; k < 8; ++k) kfs.push_back(builder.add_keyframe(test::pose_at(0.05 * k)));
  const LocalBundleAdjustmentProblem all = gather_local_window(*kfs[7], LocalWindowOptions{0, 0, 0, 0});
  ASSERT_EQ(all.keyframes.size(), 8u);

  LocalWindowOptions budget;
  budget.max_keyframes = 3;
  budget.max_fixed_keyframes = 2;
  budget.max_points = 0;
  budget.max_observations = static_cast<int>(all.ba_observations.size() / 2);
  const LocalBundleAdjustmentProblem p = gather_local_window(*kfs[7], budget);
  int free_keyframes = 0, fixed = 0;
  for (const auto& k : p.ba_keyframes) (k.fixed ? fixed : free_keyframes) += 1;
  // The new keyframe and its two heaviest covisibles are free (the origin, if
  // picked, would be fixed), at most two observers are fixed.
  EXPECT_EQ(p.keyframes[0], kfs[7]);
  EXPECT_EQ(p.keyframes[1], kfs[7]->covisibles()[0]->shared_from_this());
  EXPECT_EQ(p.keyframes[2], kfs[7]->covisibles()[1]->shared_from_this());
  EXPECT_EQ(free_keyframes + fixed, 5);
  EXPECT_LE(p.ba_observations.size(), all.ba_observations.size() / 2);
  EXPECT_GT(p.ba_observations.size(), all.ba_observations.size() / 4);
  EXPECT_LT(p.points.size(), all.points.size());
  // The new keyframe's points come first.
  EXPECT_TRUE(p.points.front()->is_observed_by(kfs[7].get()));

  budget.max_observations = 0;
  budget.max_points = 100;
  EXPECT_EQ(gather_local_window(*kfs[7], budget).points.size(), 100u);
}

TEST(LocalBundleAdjustment, ReducesInjectedNoiseAndRemovesOutliers) {
  test::SyntheticScene scene;
  test::MapBuilder builder(scene);
  std::vector<KeyFramePtr> kfs;
  std::vector<Eigen::Isometry3d> truth;
  for (int k = 0; k < 5; ++k) {
    truth.push_back(test::pose_at(0.1 * k, 0.02 * k, 2.0 * k));
    kfs.push_back(builder.add_keyframe(truth.back()));
  }
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0, 0.01);
  for (int k = 1; k < 5; ++k) {
    Eigen::Isometry3d T = kfs[k]->T_cam_world();
    T.pretranslate(Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
    kfs[k]->set_pose(T);
  }
  for (const auto& [id, mp] : builder.points()) {
    mp->set_position(mp->position() + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
  }
  // One gross outlier observation: move a keypoint's point far away in one view
  // by attaching the wrong map point to a slot.
  const std::size_t bad_slot = 5;
  MapPointPtr wrong = kfs[4]->map_point(200);
  MapPointPtr original = kfs[4]->map_point(bad_slot);
  original->erase_observation(kfs[4].get());
  kfs[4]->set_map_point(bad_slot, wrong);
  // (wrong is already observed in slot 200; observe it in the bad slot instead.)
  wrong->erase_observation(kfs[4].get());
  kfs[4]->erase_map_point(200);
  wrong->add_observation(kfs[4].get(), bad_slot);

  auto pose_error = [&] {
    double e = 0;
    for (int k = 1; k < 5; ++k) e += (kfs[k]->camera_center() - truth[k].inverse().translation()).norm();
    return e / 4;
  };
  const double before = pose_error();
  const LocalBundleAdjustmentProblem p = gather_local_window(*kfs[4]);
  const BundleAdjustmentResult r = solve_local_window(kfs[4]->setup().camera, p, LocalMapperOptions::default_bundle_adjustment());
  const LocalBundleAdjustmentStats s = apply_local_window(p, r);
  const double after = pose_error();
  std::cout << "mean camera error before " << before << " m, after " << after << " m, outliers " << s.outliers << "\n";
  EXPECT_GT(before, 0.005);
  EXPECT_LT(after, before / 5);
  EXPECT_GE(s.outliers, 1);
  EXPECT_FALSE(wrong->is_observed_by(kfs[4].get()));
  EXPECT_EQ(kfs[4]->map_point(bad_slot), nullptr);
}

TEST(LocalBundleAdjustment, PointsOnAKeptPersonStayOutOfTheWindowWhenAsked) {
  test::SyntheticScene scene;
  test::MapBuilder builder(scene);
  std::vector<KeyFramePtr> kfs;
  for (int k = 0; k < 4; ++k) kfs.push_back(builder.add_keyframe(test::pose_at(0.1 * k, 0.02 * k, 2.0 * k)));
  // Every third point flagged as seen on a person kept as static, and moved
  // 3 cm from where its observations put it (the person swayed).
  std::vector<MapPointPtr> flagged;
  std::vector<Eigen::Vector3d> moved;
  std::size_t flagged_observations = 0, all_observations = 0;
  for (const auto& [id, mp] : builder.points()) {
    all_observations += mp->observations().size();
    if (id % 3 != 0) continue;
    mp->mark_on_dynamic_instance();
    mp->set_position(mp->position() + Eigen::Vector3d(0.03, -0.02, 0.01));
    flagged.push_back(mp);
    moved.push_back(mp->position());
    flagged_observations += mp->observations().size();
  }
  ASSERT_GT(flagged.size(), 50u);

  const LocalBundleAdjustmentProblem with = gather_local_window(*kfs[3]);
  EXPECT_EQ(with.points.size(), builder.map().num_map_points());
  LocalWindowOptions out;
  out.leave_out_kept_points = true;
  const LocalBundleAdjustmentProblem without = gather_local_window(*kfs[3], out);
  EXPECT_EQ(without.points.size(), builder.map().num_map_points() - flagged.size());
  EXPECT_EQ(without.ba_observations.size(), all_observations - flagged_observations);
  for (const auto& mp : without.points) EXPECT_FALSE(mp->on_dynamic_instance());

  // Left out, the flagged points keep their (moved) places; in the window, BA
  // pulls them back toward where their observations agree.
  const auto options = LocalMapperOptions::default_bundle_adjustment();
  apply_local_window(without, solve_local_window(kfs[3]->setup().camera, without, options));
  for (std::size_t i = 0; i < flagged.size(); ++i) EXPECT_EQ(flagged[i]->position(), moved[i]);
  apply_local_window(with, solve_local_window(kfs[3]->setup().camera, with, options));
  int pulled = 0;
  for (std::size_t i = 0; i < flagged.size(); ++i) {
    if (!flagged[i]->is_bad() && (flagged[i]->position() - moved[i]).norm() > 0.01) ++pulled;
  }
  EXPECT_GT(pulled, static_cast<int>(flagged.size()) / 2);
}

TEST(PointCulling, RecentPointsNeedObservationsAndFoundRatio) {
  test::SyntheticScene scene;
  test::MapBuilder builder(scene);
  KeyFramePtr kf0 = builder.add_keyframe(test::pose_at(0));
  std::vector<MapPointPtr> recent;
  for (const auto& mp : kf0->map_points()) recent.push_back(mp);
  ASSERT_GT(recent.size(), 10u);
  // Point 0: rarely found when visible -> culled at once.
  recent[0]->increase_visible(10);
  // At keyframe id 1 (age 1) only the found-ratio rule applies.
  EXPECT_EQ(cull_recent_points(recent, 1), 1);
  EXPECT_TRUE(kf0->map_point(0) == nullptr);
  // At age 2, points with one stereo observation (count 2 <= 3) are culled.
  const std::size_t left = recent.size();
  EXPECT_EQ(cull_recent_points(recent, 2), static_cast<int>(left));
  EXPECT_TRUE(recent.empty());
}

}  // namespace
}  // namespace stillslam
