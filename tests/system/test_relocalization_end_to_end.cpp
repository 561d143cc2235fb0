// End to end with the committed vocabulary: 15 black frames in the middle of a
// synthetic sequence make tracking lose the map; when the images come back the
// camera has moved on (60 rendered frames are left out), and the tracker must
// relocalize (place recognition -> Relocalizer) within 10 frames and stay
// accurate afterwards.
#include <gtest/gtest.h>

#include <filesystem>

#include "stillslam/eval/evaluate.h"
#include "stillslam/system/system.h"
#include "system/sim_sequence.h"

namespace stillslam {
namespace {

constexpr std::size_t kBlankBegin = 40;
constexpr std::size_t kBlankEnd = 55;  // first frame with an image again
// Frames of the rendered sequence left out after the blank (2 s of camera
// motion): too far for the wide-window search of the last local map, so only
// relocalization recovers (checked below without a vocabulary).
constexpr std::size_t kSkippedFrames = 60;

std::filesystem::path vocabulary_file() {
  return std::filesystem::path(STILLSLAM_SOURCE_DIR) / "vocab" / "orb_vocabulary.bin";
}

// Frames [kBlankBegin, kBlankEnd) are black, and the skip frames after them
// are left out, so that the camera has moved on when the images come back.
test::SimSequence sequence_with_blank(std::size_t skip) {
  test::SimSequence seq = test::render_sim_sequence("walking_xyz", static_cast<int>(90 + skip), 320, 240, false);
  for (std::size_t i = kBlankBegin; i < kBlankEnd; ++i) {
    SensorFrame& f = seq.frames[i];
    f.gray.setTo(0);
    f.color.setTo(0);
  }
  seq.frames.erase(seq.frames.begin() + kBlankEnd, seq.frames.begin() + kBlankEnd + skip);
  seq.groundtruth.erase(seq.groundtruth.begin() + kBlankEnd, seq.groundtruth.begin() + kBlankEnd + skip);
  for (std::size_t i = 0; i < seq.frames.size(); ++i) seq.frames[i].index = i;
  return seq;
}

struct Outcome {
  std::vector<FrameStats> frames;
  Trajectory trajectory;
  LoopCloserStats loop_closer;
};

Outcome run(const test::SimSequence& seq, const std::filesystem::path& vocabulary) {
  SystemOptions options;
  options.deterministic = true;
  options.vocabulary_path = vocabulary;
  Settings settings = seq.settings;
  settings.tracking.init_min_keypoints = 300;
  System system(settings, SensorType::Rgbd, seq.stereo, options);
  Outcome out;
  for (const SensorFrame& f : seq.frames) {
    FrameStats stats = system.process(f);
    mark_start_frames_posed(out.frames, stats);  // the frames the map's start waited on
    out.frames.push_back(std::move(stats));
  }
  system.shutdown();
  out.trajectory = system.trajectory();
  out.loop_closer = system.loop_closer_stats();
  return out;
}

// Translation error of each estimated pose against the ground truth, both
// expressed relative to the first frame (the system's world frame).
std::vector<std::pair<double, double>> errors_by_time(const test::SimSequence& seq, const Trajectory& estimate) {
  const Eigen::Isometry3d T_cam0_world = seq.groundtruth.front().T_world_cam.inverse();
  std::vector<std::pair<double, double>> out;
  for (const StampedPose& p : estimate) {
    for (const StampedPose& g : seq.groundtruth) {
      if (std::abs(g.timestamp - p.timestamp) > 1e-6) continue;
      const Eigen::Vector3d t_gt = (T_cam0_world * g.T_world_cam).translation();
      out.emplace_back(p.timestamp, (t_gt - p.T_world_cam.translation()).norm());
    }
  }
  return out;
}

TEST(RelocalizationEndToEnd, RelocalizesAfterBlankFramesAndStaysAccurate) {
  if (!std::filesystem::exists(vocabulary_file())) GTEST_SKIP() << "no " << vocabulary_file();
  const test::SimSequence seq = sequence_with_blank(kSkippedFrames);
  const Outcome out = run(seq, vocabulary_file());

  // Tracked before the blank, lost during it.
  for (std::size_t i = 0; i < kBlankBegin; ++i) EXPECT_TRUE(out.frames[i].has_pose) << "frame " << i;
  for (std::size_t i = kBlankBegin; i < kBlankEnd; ++i) {
    EXPECT_EQ(out.frames[i].state, TrackingState::Lost) << "frame " << i;
  }
  // Relocalized within 10 frames after the blank, then tracked to the end.
  std::size_t relocalized_at = out.frames.size();
  for (std::size_t i = kBlankEnd; i < out.frames.size(); ++i) {
    if (out.frames[i].reason == "relocalized") {
      relocalized_at = i;
      break;
    }
  }
  std::cout << "relocalized at frame " << relocalized_at << " (blank " << kBlankBegin << ".." << kBlankEnd - 1
            << "), loop closer saw " << out.loop_closer.keyframes << " keyframes\n";
  ASSERT_LT(relocalized_at, kBlankEnd + 10);
  for (std::size_t i = relocalized_at; i < out.frames.size(); ++i) {
    EXPECT_TRUE(out.frames[i].has_pose) << "frame " << i;
  }
  EXPECT_GT(out.loop_closer.keyframes, 0);

  // Accurate after relocalization, in the same world frame as before the loss
  // (no alignment: a wrong relocalization would show as an offset).
  const double t_reloc = seq.frames[relocalized_at].timestamp;
  double max_after = 0;
  int poses_after = 0;
  for (const auto& [t, e] : errors_by_time(seq, out.trajectory)) {
    if (t + 1e-9 < t_reloc) continue;
    max_after = std::max(max_after, e);
    ++poses_after;
  }
  std::cout << "after relocalization: " << poses_after << " poses, max translation error " << max_after << " m\n";
  EXPECT_EQ(poses_after, static_cast<int>(out.frames.size() - relocalized_at));
  EXPECT_LT(max_after, 0.02);
  // And over the whole run (SE3-aligned ATE).
  const EvaluationResult ev = evaluate(seq.groundtruth, out.trajectory, EvaluationOptions{});
  std::cout << "ATE rmse " << ev.ape_stats.rmse << " m over " << ev.pairs << " poses\n";
  EXPECT_LT(ev.ape_stats.rmse, 0.01);

  // Without a vocabulary only the wide-window search of the last local map is left.
  const Outcome without = run(seq, {});
  int recovered_without = 0;
  for (std::size_t i = kBlankEnd; i < without.frames.size(); ++i) recovered_without += without.frames[i].has_pose ? 1 : 0;
  std::cout << "without vocabulary: " << recovered_without << " of " << without.frames.size() - kBlankEnd
            << " frames after the blank tracked\n";
  EXPECT_EQ(recovered_without, 0) << "the camera must move further during the blank, else this test does not "
                                     "need relocalization";
}

}  // namespace
}  // namespace stillslam
