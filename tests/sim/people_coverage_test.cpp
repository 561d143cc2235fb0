// People cross the camera's view on every generated camera path: they enter
// and leave it, cross in front of the camera and at times cover a large part
// of the image, without ever standing in furniture or near the camera. The
// occluder hides (nearly) the whole view for its time.
#include <gtest/gtest.h>

#include <filesystem>

#include "stillslam/sim/simulator.h"

namespace stillslam::sim {
namespace {
namespace fs = std::filesystem;

SimulationOptions small(const char* trajectory) {
  SimulationOptions o;
  o.width = 160;
  o.height = 120;
  o.supersampling = 1;
  o.people = 3;
  o.frames = 800;
  o.trajectory = trajectory;
  o.data_dir = fs::path(STILLSLAM_SOURCE_DIR) / "data";
  return o;
}

constexpr double o_fps = 30.0;

double masked_fraction(const SimFrame& f) { return cv::countNonZero(f.mask) / static_cast<double>(f.mask.total()); }

TEST(PeopleCoverage, PeopleCrossTheViewOnEveryGeneratedPath) {
  const std::vector<std::pair<const char*, double>> cases = {{"walking_xyz", 0.25}, {"halfsphere", 0.25}, {"rpy", 0.25}};
  for (const auto& [trajectory, min_peak] : cases) {
    const Simulator sim(small(trajectory));
    WalkingPathOptions clearance;  // paths are checked every 5 cm; between checks 5 cm of body remain
    clearance.body_radius = 0.05;
    clearance.wall_clearance = 0.2;
    const WalkingPathPlanner planner({}, clearance);
    for (const WalkingPath& p : sim.dynamic_objects().walking_paths()) {
      EXPECT_GE(p.distance, 0.6) << trajectory;
      for (double s = 0; s <= 1.0; s += 0.01) EXPECT_TRUE(planner.free(p.a + s * (p.b - p.a))) << trajectory;
    }
    int frames = 0, covered = 0;
    double peak = 0;
    for (int i = 0; i < sim.frame_count(); i += 10) {
      const SimFrame f = sim.render_frame(i);
      const double frac = masked_fraction(f);
      ++frames;
      covered += frac >= 0.05;
      peak = std::max(peak, frac);
      // Nobody next to or behind the camera: every walking person's feet stay 0.5 m away.
      const Eigen::Vector3d cam = sim.T_world_scene().inverse() * f.T_world_cam.translation();
      for (const PersonTrack& p : sim.dynamic_objects().people()) {
        const Eigen::Vector3d foot = sim.dynamic_objects().person_foot(p, i / o_fps);
        EXPECT_GT((foot - cam).head<2>().norm(), 0.5) << trajectory << " frame " << i;
      }
    }
    EXPECT_GE(covered, 0.3 * frames) << trajectory;
    EXPECT_GE(peak, min_peak) << trajectory;
  }
}

TEST(PeopleCoverage, OccluderHidesTheViewForItsTime) {
  SimulationOptions o = small("halfsphere");
  o.people = 0;
  o.frames = 150;
  o.occlude_at = 2.0;
  o.occlude_seconds = 1.5;
  const Simulator sim(o);
  EXPECT_NE(sim.dynamic_objects().occluder_id(), 0);
  EXPECT_EQ(cv::countNonZero(sim.render_frame(30).mask), 0);            // 1.0 s: not yet
  EXPECT_GT(masked_fraction(sim.render_frame(60)), 0.9);                 // 2.0 s
  EXPECT_GT(masked_fraction(sim.render_frame(80)), 0.9);
  EXPECT_GT(masked_fraction(sim.render_frame(104)), 0.9);                // 3.47 s
  EXPECT_EQ(cv::countNonZero(sim.render_frame(120).mask), 0);           // 4.0 s: gone
  o.no_people = true;  // the static reference has no occluder
  EXPECT_EQ(cv::countNonZero(Simulator(o).render_frame(80).mask), 0);
}

TEST(PeopleCoverage, CrowdCoversMostOfTheViewForItsTime) {
  for (const auto& [path, seed] : {std::pair{"walking_xyz", 0}, std::pair{"halfsphere", 0}, std::pair{"walking_xyz", 7},
                                   std::pair{"rpy", 4}}) {
    SimulationOptions o = small(path);
    o.seed = seed;
    o.people = 0;
    o.frames = 300;
    o.crowd_at = 3.0;
    o.crowd_seconds = 2.0;
    const Simulator sim(o);
    const std::vector<CrowdMember>& crowd = sim.dynamic_objects().crowd();
    ASSERT_GE(crowd.size(), 6u) << path;
    EXPECT_EQ(cv::countNonZero(sim.render_frame(0).mask), 0) << path;  // not yet in view
    double least = 1;
    for (int frame = 90; frame <= 150; frame += 10) least = std::min(least, masked_fraction(sim.render_frame(frame)));
    EXPECT_GT(least, 0.5) << path;  // 3.0-5.0 s: most of the view
    EXPECT_EQ(cv::countNonZero(sim.render_frame(299).mask), 0) << path;  // 10 s: all gone
    // Members are in the scene only while they walk.
    for (const CrowdMember& m : crowd) {
      EXPECT_TRUE(sim.dynamic_objects().crowd_foot(m, m.t_start + 0.1).has_value());
      EXPECT_FALSE(sim.dynamic_objects().crowd_foot(m, m.t_start - 0.1).has_value());
    }
  }
  SimulationOptions o = small("walking_xyz");
  o.frames = 300;
  o.crowd_at = 3.0;
  o.no_people = true;  // the static reference has no crowd
  EXPECT_EQ(cv::countNonZero(Simulator(o).render_frame(120).mask), 0);
}

// The moved box and the pushed chair are in view while they move (the chair
// only in part of it on some paths: it starts behind the desk's clutter).
TEST(PeopleCoverage, MovedBoxAndChairAreSeenWhileTheyMove) {
  for (const char* path : {"walking_xyz", "halfsphere", "static"}) {
    SimulationOptions o = small(path);
    o.people = 0;
    o.frames = 300;  // 10 s: the box moves over 4-6.5 s, the chair over 6.5-8.5 s
    o.moved_object = true;
    o.moved_chair = true;
    const Simulator sim(o);
    const std::vector<InstanceInfo> instances = sim.dynamic_objects().instances();
    ASSERT_EQ(instances.size(), 2u);
    auto share = [&](int frame, std::uint16_t id) {
      return cv::countNonZero(sim.render_frame(frame).dynamic_ids == id) / double(o.width * o.height);
    };
    for (int frame : {130, 160, 190}) EXPECT_GT(share(frame, instances[0].id), 0.003) << path << " box " << frame;
    int chair_frames = 0;
    for (int frame = 200; frame <= 250; frame += 10) chair_frames += share(frame, instances[1].id) > 0.003;
    EXPECT_GE(chair_frames, 3) << path;
    EXPECT_EQ(share(100, instances[0].id) + share(270, instances[1].id), 0) << path;  // at rest: part of the room
  }
}

}  // namespace
}  // namespace stillslam::sim
