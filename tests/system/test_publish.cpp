// The publish layer end to end: what System posts after each frame matches
// what it reports, readers on another thread see consistent snapshots while
// the threads run, and the progress line reads them.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <thread>

#include "stillslam/core/error.h"
#include "stillslam/system/progress.h"
#include "stillslam/system/system.h"
#include "system/sim_sequence.h"

namespace stillslam {
namespace {

const test::SimSequence& sequence() {
  static const test::SimSequence seq = [] {
    test::SimSequence s = test::render_sim_sequence("walking_xyz", 40, 320, 240, false);
    s.settings.tracking.init_min_keypoints = 300;
    return s;
  }();
  return seq;
}

TEST(Publish, SnapshotsMatchWhatTheSystemReports) {
  const test::SimSequence& seq = sequence();
  SystemOptions options;
  options.deterministic = true;
  options.publish.map_every_frames = 1;
  System system(seq.settings, SensorType::Rgbd, seq.stereo, options);
  EXPECT_EQ(system.publisher().frame().version, 0u);
  int keyframes = 0;
  for (std::size_t i = 0; i < seq.frames.size(); ++i) {
    const FrameStats stats = system.process(seq.frames[i]);
    keyframes += stats.keyframe ? 1 : 0;
    const Publisher::FrameRead frame = system.publisher().frame();
    ASSERT_EQ(frame.version, i + 1);
    EXPECT_EQ(frame.value->index, stats.index);
    EXPECT_EQ(frame.value->state, to_string(stats.state));
    EXPECT_EQ(static_cast<int>(frame.value->keypoints.size()), stats.build.keypoints_after);
    ASSERT_EQ(frame.value->tracked.size(), frame.value->keypoints.size());
    const auto tracked = std::count(frame.value->tracked.begin(), frame.value->tracked.end(), true);
    if (stats.state == TrackingState::Ok && i > 0) {
      EXPECT_GE(tracked, stats.inliers / 2);
    }
    EXPECT_EQ(frame.value->has_pose, stats.has_pose);
    if (stats.has_pose) {
      EXPECT_LT((frame.value->T_world_cam.translation() - system.last_T_world_cam()->translation()).norm(), 1e-12);
    }
    const Publisher::AtlasRead atlas = system.publisher().atlas();
    ASSERT_TRUE(atlas.value);
    EXPECT_EQ(atlas.value->frame_id, frame.value->frame_id);
    EXPECT_EQ(atlas.value->num_keyframes(), system.num_keyframes());
    EXPECT_EQ(atlas.value->num_points(), system.num_map_points());
  }
  ASSERT_GE(keyframes, 2);
  const Publisher::AtlasRead atlas = system.publisher().atlas();
  ASSERT_EQ(atlas.value->maps.size(), 1u);
  const MapSnapshot& map = atlas.value->maps[0];
  EXPECT_TRUE(map.active);
  // Every tracked frame is on the map's trajectory, and the keyframes are
  // linked by strong covisibility edges.
  EXPECT_EQ(map.trajectory.size(), system.trajectory().size());
  EXPECT_FALSE(map.covisibility.empty());
  for (const auto& [a, b] : map.covisibility) {
    EXPECT_LT(a, b);
    EXPECT_LT(b, map.keyframes.size());
  }
}

TEST(Publish, MapSnapshotsComeOnKeyframesAndEveryNFrames) {
  const test::SimSequence& seq = sequence();
  SystemOptions options;
  options.deterministic = true;
  options.publish.map_every_frames = 0;  // only on map events
  System system(seq.settings, SensorType::Rgbd, seq.stereo, options);
  std::uint64_t versions = 0;
  int keyframes = 0;
  for (const SensorFrame& f : seq.frames) {
    keyframes += system.process(f).keyframe ? 1 : 0;
    versions = system.publisher().atlas().version;
  }
  EXPECT_EQ(versions, static_cast<std::uint64_t>(keyframes));
  options.publish.map_every_frames = -1;
  EXPECT_THROW(System(seq.settings, SensorType::Rgbd, seq.stereo, options), Error);
}

TEST(Publish, ReadersOnAnotherThreadWhileTheStagesRun) {
  const test::SimSequence& seq = sequence();
  SystemOptions options;  // threaded local mapping and loop closing
  options.vocabulary_path = std::filesystem::path(STILLSLAM_SOURCE_DIR) / "vocab" / "orb_vocabulary.bin";
  System system(seq.settings, SensorType::Rgbd, seq.stereo, options);
  std::atomic<bool> done{false};
  std::size_t reads = 0, points_seen = 0;
  std::uint64_t last_version = 0;
  bool versions_increase = true;
  std::thread reader([&] {
    while (!done) {
      const Publisher::FrameRead frame = system.publisher().wait_frame(last_version, std::chrono::milliseconds(50));
      if (frame.version < last_version) versions_increase = false;
      last_version = frame.version;
      if (const Publisher::AtlasRead atlas = system.publisher().atlas(); atlas.value) {
        for (const MapSnapshot& m : atlas.value->maps) points_seen = std::max(points_seen, m.points.size());
      }
      ++reads;
    }
  });
  for (const SensorFrame& f : seq.frames) system.process(f);
  system.shutdown();
  done = true;
  reader.join();
  EXPECT_TRUE(versions_increase);
  EXPECT_GT(reads, 0u);
  EXPECT_GT(points_seen, 100u);
  EXPECT_EQ(system.publisher().frame().version, seq.frames.size());
}

TEST(Progress, LineNamesFramesRateStateMapAndEta) {
  FrameSnapshot frame;
  frame.state = "ok";
  frame.map_id = 1;
  AtlasSnapshot atlas;
  MapSnapshot other, active;
  other.map_id = 0;
  active.map_id = 1;
  active.keyframes.resize(12);
  active.points.resize(3400);
  atlas.maps = {other, active};
  atlas.loops_closed = 2;
  EXPECT_EQ(format_progress(frame, &atlas, 50, 200, 5.0),
            "frame 50/200 (25.0%)  10.0 fps  ok  map 1: 12 kf, 3400 pts  (2 maps)  loops 2  ETA 15s");
  EXPECT_EQ(format_progress(frame, nullptr, 7, 0, 2.0), "frame 7  3.5 fps  ok");
  EXPECT_EQ(format_progress(frame, nullptr, 10, 10000, 1.0), "frame 10/10000 (0.1%)  10.0 fps  ok  ETA 16m39s");
}

TEST(Progress, PlainLinesFromTheNewestSnapshot) {
  Publisher publisher;
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  {
    ProgressReporter progress(publisher, {.total_frames = 4, .terminal = false,
                                          .plain_interval = std::chrono::milliseconds(5)}, out);
    for (std::uint64_t i = 0; i < 4; ++i) {
      auto f = std::make_shared<FrameSnapshot>();
      f->frame_id = i;
      f->state = "ok";
      publisher.publish_frame(f);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  std::rewind(out);
  char line[256];
  int lines = 0;
  std::string last;
  while (std::fgets(line, sizeof line, out)) {
    ++lines;
    last = line;
  }
  std::fclose(out);
  EXPECT_GE(lines, 2);
  EXPECT_EQ(last.rfind("frame 4/4 (100.0%)", 0), 0u) << last;
}

}  // namespace
}  // namespace stillslam
