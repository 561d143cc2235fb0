// Atlas end to end on a rendered sequence: 5 black frames make tracking lose
// the map, then 10 frames of noise texture without depth (plenty of
// keypoints, but a place no map has seen) make relocalization fail; after
// those 10 failures (black frames do not count) a new map starts and
// initializes from the first real frame again. Black frames alone do not count as failed
// relocalizations (BlackFramesDoNotStartANewMap). Without merging the
// frames after the gap are tracked in map 1 and those before stay in map 0;
// with merging the new map is recognized in the old one and merged back, and
// the whole trajectory is in one frame again.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "stillslam/eval/evaluate.h"
#include "stillslam/system/system.h"
#include "system/sim_sequence.h"

namespace stillslam {
namespace {

constexpr std::size_t kBlankBegin = 40;
constexpr std::size_t kBlankEnd = 55;  // first frame with an image again
constexpr int kLostFramesForNewMap = 10;
constexpr std::size_t kNoiseBegin = kBlankEnd - kLostFramesForNewMap;  // black before, noise from here

std::filesystem::path vocabulary_file() {
  return std::filesystem::path(STILLSLAM_SOURCE_DIR) / "vocab" / "orb_vocabulary.bin";
}

test::SimSequence sequence_with_gap(bool noise) {
  test::SimSequence seq = test::render_sim_sequence("walking_xyz", 120, 320, 240, false);
  for (std::size_t i = kBlankBegin; i < kBlankEnd; ++i) {
    SensorFrame& f = seq.frames[i];
    if (noise && i >= kNoiseBegin) {
      cv::RNG rng(i);
      rng.fill(f.gray, cv::RNG::UNIFORM, 0, 256);
      if (!f.color.empty()) cv::cvtColor(f.gray, f.color, cv::COLOR_GRAY2BGR);
      f.depth.setTo(0);
    } else {
      f.gray.setTo(0);
      f.color.setTo(0);
    }
  }
  return seq;
}

struct Outcome {
  std::vector<FrameStats> frames;
  std::vector<MapPose> trajectory;
  std::size_t maps = 0;
  int new_maps = 0;
  std::vector<MapMergeStats> merges;
};

Outcome run(const test::SimSequence& seq, bool merging, int new_map_after = kLostFramesForNewMap,
            bool deterministic = true) {
  SystemOptions options;
  options.deterministic = deterministic;
  options.vocabulary_path = vocabulary_file();
  options.new_map_after_lost_frames = new_map_after;
  Settings settings = seq.settings;
  settings.tracking.init_min_keypoints = 300;
  settings.map_merging = merging;
  System system(settings, SensorType::Rgbd, seq.stereo, options);
  Outcome out;
  for (const SensorFrame& f : seq.frames) {
    FrameStats stats = system.process(f);
    mark_start_frames_posed(out.frames, stats);  // the frames the map's start waited on
    out.frames.push_back(std::move(stats));
  }
  system.shutdown();
  out.trajectory = system.trajectory_with_maps();
  out.maps = system.num_maps();
  out.new_maps = system.new_maps_started();
  out.merges = system.merges();
  return out;
}

Trajectory poses_of(const std::vector<MapPose>& t, std::optional<std::uint64_t> map_id = std::nullopt) {
  Trajectory out;
  for (const MapPose& p : t) {
    if (!map_id || p.map_id == *map_id) out.push_back(p.pose);
  }
  return out;
}

TEST(AtlasEndToEnd, NewMapAfterRepeatedRelocalizationFailure) {
  if (!std::filesystem::exists(vocabulary_file())) GTEST_SKIP() << "no " << vocabulary_file();
  const test::SimSequence seq = sequence_with_gap(true);
  const Outcome out = run(seq, false);

  for (std::size_t i = 0; i < kBlankBegin; ++i) {
    EXPECT_TRUE(out.frames[i].has_pose) << i;
    EXPECT_EQ(out.frames[i].map_id, 0u) << i;
  }
  const std::size_t switch_frame = kBlankEnd - 1;  // the 10th noise frame
  for (std::size_t i = kBlankBegin; i <= switch_frame; ++i) {
    EXPECT_EQ(out.frames[i].state, TrackingState::Lost) << i;
    EXPECT_EQ(out.frames[i].new_map, i == switch_frame) << i;
  }
  for (std::size_t i = switch_frame + 1; i < kBlankEnd; ++i) {
    EXPECT_EQ(out.frames[i].state, TrackingState::NotInitialized) << i;  // no depth: no map to start
  }
  // The new map starts from the first frame with an image, confirmed by the 3
  // next (Tracking.initUnmaskedConfirmFrames), which poses the 3 it waited on.
  for (std::size_t i = kBlankEnd; i < kBlankEnd + 3; ++i) {
    EXPECT_EQ(out.frames[i].state, TrackingState::NotInitialized) << i;
    EXPECT_TRUE(out.frames[i].posed_at_start) << i;
  }
  EXPECT_NE(out.frames[kBlankEnd + 3].reason.find("map started at frame " + std::to_string(kBlankEnd)),
            std::string::npos)
      << out.frames[kBlankEnd + 3].reason;
  ASSERT_EQ(out.frames[kBlankEnd + 3].start_frames_posed.size(), 3u);
  EXPECT_EQ(out.frames[kBlankEnd + 3].start_frames_posed.front().index, kBlankEnd);
  for (std::size_t i = kBlankEnd; i < out.frames.size(); ++i) {
    EXPECT_TRUE(out.frames[i].has_pose) << i;
    EXPECT_EQ(out.frames[i].map_id, 1u) << i;
  }
  EXPECT_EQ(out.new_maps, 1);
  EXPECT_EQ(out.maps, 2u);
  EXPECT_TRUE(out.merges.empty());

  // Frames before the gap in map 0, after it in map 1, each accurate in its own frame.
  const Trajectory map0 = poses_of(out.trajectory, 0), map1 = poses_of(out.trajectory, 1);
  EXPECT_EQ(map0.size(), kBlankBegin);
  EXPECT_EQ(map1.size(), seq.frames.size() - kBlankEnd);
  const double ate0 = evaluate(seq.groundtruth, map0, EvaluationOptions{}).ape_stats.rmse;
  const double ate1 = evaluate(seq.groundtruth, map1, EvaluationOptions{}).ape_stats.rmse;
  std::cout << "map 0: " << map0.size() << " poses, ATE " << ate0 << " m; map 1: " << map1.size()
            << " poses, ATE " << ate1 << " m\n";
  EXPECT_LT(ate0, 0.01);
  EXPECT_LT(ate1, 0.01);
  // Map 1 starts at its own origin: its first pose is the identity.
  EXPECT_LT(map1.front().T_world_cam.translation().norm(), 1e-9);
}

TEST(AtlasEndToEnd, NewMapIsMergedBackIntoTheOldOne) {
  if (!std::filesystem::exists(vocabulary_file())) GTEST_SKIP() << "no " << vocabulary_file();
  const test::SimSequence seq = sequence_with_gap(true);
  const Outcome out = run(seq, true);

  EXPECT_EQ(out.new_maps, 1);
  ASSERT_EQ(out.merges.size(), 1u);
  EXPECT_EQ(out.merges[0].source_map, 1u);
  EXPECT_EQ(out.merges[0].target_map, 0u);
  EXPECT_EQ(out.maps, 1u);
  std::size_t merged_at = 0;
  for (std::size_t i = 0; i < out.frames.size(); ++i) {
    if (out.frames[i].merged) merged_at = i;
  }
  std::cout << "new map at frame " << kBlankEnd << ", merged at frame " << merged_at << " ("
            << out.merges[0].inliers << " inliers, " << out.merges[0].fused_points << " points fused)\n";
  EXPECT_GT(merged_at, kBlankEnd);
  for (std::size_t i = merged_at + 1; i < out.frames.size(); ++i) {
    EXPECT_TRUE(out.frames[i].has_pose) << i;
    EXPECT_EQ(out.frames[i].map_id, 0u) << i;
  }
  // Every tracked frame, before and after the gap, in map 0's frame.
  for (const MapPose& p : out.trajectory) EXPECT_EQ(p.map_id, 0u);
  EXPECT_EQ(out.trajectory.size(), seq.frames.size() - (kBlankEnd - kBlankBegin));
  const EvaluationResult ev = evaluate(seq.groundtruth, poses_of(out.trajectory), EvaluationOptions{});
  std::cout << "ATE over the whole sequence after the merge: " << ev.ape_stats.rmse << " m (max "
            << ev.ape_stats.max << ") over " << ev.pairs << " poses\n";
  EXPECT_LT(ev.ape_stats.rmse, 0.01);
}

// The same with local mapping and loop closing on their threads: the stages
// are flushed and moved to the new map, then to the merged one, while
// tracking goes on (the ThreadSanitizer job runs this one).
TEST(AtlasEndToEnd, ThreadedStagesFollowTheNewMapAndTheMerge) {
  if (!std::filesystem::exists(vocabulary_file())) GTEST_SKIP() << "no " << vocabulary_file();
  const test::SimSequence seq = sequence_with_gap(true);
  const Outcome out = run(seq, true, kLostFramesForNewMap, false);
  EXPECT_EQ(out.new_maps, 1);
  ASSERT_EQ(out.merges.size(), 1u);
  EXPECT_EQ(out.maps, 1u);
  for (const MapPose& p : out.trajectory) EXPECT_EQ(p.map_id, 0u);
  const EvaluationResult ev = evaluate(seq.groundtruth, poses_of(out.trajectory), EvaluationOptions{});
  EXPECT_LT(ev.ape_stats.rmse, 0.02);
}

// The same gap all black: relocalization never had an image to work on, so
// no new map starts however long the blank; the camera is relocalized in map
// 0 at the first frame with an image again.
TEST(AtlasEndToEnd, BlackFramesDoNotStartANewMap) {
  if (!std::filesystem::exists(vocabulary_file())) GTEST_SKIP() << "no " << vocabulary_file();
  const test::SimSequence seq = sequence_with_gap(false);
  const Outcome out = run(seq, true, 5);
  EXPECT_EQ(out.new_maps, 0);
  EXPECT_EQ(out.maps, 1u);
  for (std::size_t i = kBlankBegin; i < kBlankEnd; ++i) EXPECT_EQ(out.frames[i].state, TrackingState::Lost) << i;
  EXPECT_EQ(out.frames[kBlankEnd].reason, "relocalized");
  for (std::size_t i = kBlankEnd; i < out.frames.size(); ++i) {
    EXPECT_TRUE(out.frames[i].has_pose) << i;
    EXPECT_EQ(out.frames[i].map_id, 0u) << i;
  }
}

}  // namespace
}  // namespace stillslam
