// People and the moved box: continuous paths on the floor, human height,
// facing the camera, dynamic ids.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "stillslam/sim/dynamic_objects.h"

namespace stillslam::sim {
namespace {

// A camera standing at `position` looking at the desk for `seconds`.
std::vector<TimedPose> still_camera(const Eigen::Vector3d& position, double seconds) {
  std::vector<TimedPose> path;
  for (double t = 0; t <= seconds + 1e-9; t += 0.1) path.push_back({t, look_at(position, SceneLayout::desk_centre())});
  return path;
}

PeopleTextures people_textures() {
  PeopleTextures p;
  p.walking = {4, 5};
  p.walking_sizes = {{100, 300}, {120, 280}};
  p.sitting = {6};
  p.sitting_sizes = {{80, 150}};
  return p;
}

const Eigen::Vector3d kCamera(0.1, -0.2, 0.05);

// `walking` + `still` people in front of a camera standing at kCamera for `seconds`.
DynamicObjects people_in_front(int walking, int still, double seconds, std::uint64_t seed) {
  DynamicObjectsOptions o;
  o.walking = walking;
  o.still = still;
  o.duration = seconds;
  const std::vector<cv::Size> textures(4, cv::Size(640, 480));
  return DynamicObjects(o, Eigen::Isometry3d::Identity(), still_camera(kCamera, seconds), people_textures(),
                        textures, seed);
}

TEST(DynamicObjects, PeopleWalkOnTheFloorAtHumanHeightFacingTheCamera) {
  const Eigen::Vector3d& camera = kCamera;
  const DynamicObjects dyn = people_in_front(3, 1, 20, 9);
  ASSERT_EQ(dyn.people().size(), 4u);
  std::vector<Eigen::Vector3d> last(4);
  int standing_frames = 0;
  for (int k = 0; k <= 600; ++k) {
    const double t = k / 30.0;
    const std::vector<Quad> quads = dyn.quads_at(t, look_at(camera, SceneLayout::desk_centre()));
    ASSERT_EQ(quads.size(), 4u);
    for (size_t i = 0; i < quads.size(); ++i) {
      const Quad& q = quads[i];
      EXPECT_TRUE(q.alpha_tested);
      EXPECT_EQ(q.dynamic_id, dyn.people()[i].id);
      const double h = -q.axis_v.z();
      EXPECT_GT(h, dyn.people()[i].still ? 1.1 : 1.6);
      EXPECT_LT(h, 1.9);
      // Feet near the floor (bob is a few centimetres).
      const Eigen::Vector3d foot = q.origin + q.axis_u / 2 + q.axis_v;
      EXPECT_NEAR(foot.z(), SceneLayout::kFloorZ, 0.03);
      // Seen from its front: axis_u x axis_v points away from the camera.
      EXPECT_GT(q.axis_u.cross(q.axis_v).dot(foot - camera), 0);
      if (k > 0) {
        const double step = (foot - last[i]).norm();
        EXPECT_LT(step, 1.4 / 30 + 0.01) << "person " << i << " jumps at t=" << t;
        if (!dyn.people()[i].still && step < 0.003) ++standing_frames;
      }
      last[i] = foot;
    }
  }
  EXPECT_GT(standing_frames, 60);  // pauses and stops in view happen
}

TEST(DynamicObjects, PeopleWhoStopInViewShiftSlowly) {
  // Standing people drift slowly (0.05-0.4 m/s) rather than freeze: the motion
  // a geometric outlier test cannot tell from noise.
  const DynamicObjects dyn = people_in_front(3, 0, 30, 5);
  int stopping = 0, slow_frames = 0;
  for (const PersonTrack& p : dyn.people()) {
    if (p.stop_time == 0) continue;
    ++stopping;
    EXPECT_GT(p.dawdle.norm(), 0.02);
    EXPECT_LE(p.dawdle.norm(), 0.3 + 1e-9);
    for (int k = 1; k <= 900; ++k) {
      const double speed = (dyn.person_foot(p, k / 30.0) - dyn.person_foot(p, (k - 1) / 30.0)).norm() * 30;
      slow_frames += speed > 0.02 && speed < 0.4;
    }
  }
  EXPECT_EQ(stopping, 2);  // every person but the first stops
  EXPECT_GT(slow_frames, 150);
}

TEST(DynamicObjects, StillPeopleKeepFacingWhereTheCameraStarted) {
  // A camera carried 1.2 m sideways: walking people turn with it, a still
  // person keeps its facing (its texture moves by its sway only, 1 cm).
  std::vector<TimedPose> path;
  for (double t = 0; t <= 10 + 1e-9; t += 0.1) {
    path.push_back({t, look_at(kCamera + Eigen::Vector3d(0.12 * t - 0.6, 0, 0), SceneLayout::desk_centre())});
  }
  DynamicObjectsOptions o;
  o.walking = 1;
  o.still = 1;
  o.duration = 10;
  const DynamicObjects dyn(o, Eigen::Isometry3d::Identity(), path, people_textures(),
                           std::vector<cv::Size>(4, cv::Size(640, 480)), 3);
  ASSERT_EQ(dyn.people().size(), 2u);
  ASSERT_TRUE(dyn.people()[1].still);
  const std::vector<Quad> start = dyn.quads_at(0, path.front().T_world_cam);
  const std::vector<Quad> end = dyn.quads_at(10, path.back().T_world_cam);
  const auto turn = [](const Quad& a, const Quad& b) {
    return std::acos(std::clamp(a.axis_u.normalized().dot(b.axis_u.normalized()), -1.0, 1.0));
  };
  EXPECT_LT(turn(start[1], end[1]), 1e-6);
  EXPECT_GT(turn(start[0], end[0]), 0.1);
  // Its texture's corners move by the sway and bob alone.
  for (const Quad& q : {start[1], end[1]}) EXPECT_LT((q.origin - start[1].origin).norm(), 0.03);
  // It faces the camera's start: seen from its front there.
  const Eigen::Vector3d foot = start[1].origin + start[1].axis_u / 2 + start[1].axis_v;
  EXPECT_GT(start[1].axis_u.cross(start[1].axis_v).dot(foot - path.front().T_world_cam.translation()), 0);
}

TEST(DynamicObjects, BoxIsDynamicOnlyWhileCarried) {
  DynamicObjectsOptions o;
  o.walking = 0;
  o.moved_box = true;
  o.duration = 10;  // picked up at 4 s, set down at 6.5 s
  const std::vector<cv::Size> textures(2, cv::Size(64, 64));
  const DynamicObjects dyn(o, Eigen::Isometry3d::Identity(), still_camera(Eigen::Vector3d::Zero(), 10), {},
                           textures, 1);
  const Eigen::Isometry3d camera = look_at(Eigen::Vector3d::Zero(), SceneLayout::desk_centre());
  const auto before = dyn.quads_at(3.9, camera);
  const auto during = dyn.quads_at(5.0, camera);
  const auto after = dyn.quads_at(7.0, camera);
  ASSERT_EQ(before.size(), 5u);
  EXPECT_EQ(before[0].dynamic_id, 0);
  EXPECT_NE(during[0].dynamic_id, 0);
  EXPECT_EQ(after[0].dynamic_id, 0);
  EXPECT_NEAR((after[0].origin - before[0].origin).norm(), std::hypot(0.8, 0.35), 1e-9);
  EXPECT_GT(during[0].origin.z(), before[0].origin.z() + 0.1);  // lifted
}

TEST(DynamicObjects, ChairIsDynamicOnlyWhilePushedAndLeavesTheStaticScene) {
  const std::vector<cv::Size> textures(4, cv::Size(64, 64));
  std::vector<Quad> chair;
  const std::vector<Quad> with_chair = build_static_scene(Eigen::Isometry3d::Identity(), textures, 5);
  const std::vector<Quad> without = build_static_scene(Eigen::Isometry3d::Identity(), textures, 5, &chair);
  ASSERT_EQ(chair.size(), 10u);  // seat and backrest, five faces each
  ASSERT_EQ(without.size() + chair.size(), with_chair.size());
  // The rest of the room is the same panels (same random draws).
  EXPECT_EQ(without.back().texture, with_chair.back().texture);
  EXPECT_TRUE(without.back().origin.isApprox(with_chair.back().origin));
  for (const Quad& q : chair) EXPECT_NEAR(q.origin.x(), SceneLayout::chair_front(1).x(), 0.24);

  DynamicObjectsOptions o;
  o.walking = 0;
  o.moved_box = true;
  o.duration = 10;  // the chair moves from 6.5 s to 8.5 s
  const DynamicObjects dyn(o, Eigen::Isometry3d::Identity(), still_camera(Eigen::Vector3d::Zero(), 10), {},
                           textures, 1, chair);
  EXPECT_NEAR(dyn.chair_motion().first, 6.5, 1e-9);
  EXPECT_NEAR(dyn.chair_motion().second, 8.5, 1e-9);
  const Eigen::Isometry3d camera = look_at(Eigen::Vector3d::Zero(), SceneLayout::desk_centre());
  const auto before = dyn.quads_at(6.4, camera);
  const auto during = dyn.quads_at(7.5, camera);
  const auto after = dyn.quads_at(9.0, camera);
  ASSERT_EQ(before.size(), 5u + 10u);  // box then chair
  EXPECT_EQ(before[5].dynamic_id, 0);
  EXPECT_NE(during[5].dynamic_id, 0);
  EXPECT_EQ(during[0].dynamic_id, 0);  // the box is not moving then
  EXPECT_EQ(after[5].dynamic_id, 0);
  EXPECT_NEAR((after[5].origin - before[5].origin).norm(), 0.6, 1e-9);    // pushed 0.6 m to the right
  EXPECT_NEAR(after[5].origin.z(), before[5].origin.z(), 1e-12);          // not lifted

  const std::vector<InstanceInfo> instances = dyn.instances();
  ASSERT_EQ(instances.size(), 2u);
  EXPECT_EQ(instances[0].kind, "moved_box");
  EXPECT_EQ(instances[1].kind, "moved_chair");
  EXPECT_EQ(instances[1].category, "chair");
  EXPECT_EQ(instances[1].id, during[5].dynamic_id);
}

TEST(DynamicObjects, InstancesNameEveryIdAndWhetherItMoves) {
  const DynamicObjects dyn = people_in_front(2, 1, 20, 9);
  const std::vector<InstanceInfo> instances = dyn.instances();
  ASSERT_EQ(instances.size(), 3u);
  for (std::size_t i = 0; i < instances.size(); ++i) {
    EXPECT_EQ(instances[i].id, dyn.people()[i].id);
    EXPECT_EQ(instances[i].category, "person");
    EXPECT_EQ(instances[i].moves, !dyn.people()[i].still);
  }
  EXPECT_EQ(instances[2].kind, "still_person");
}

}  // namespace
}  // namespace stillslam::sim
