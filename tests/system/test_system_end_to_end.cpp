// End to end on short synthetic sequences (static scene, exact ground truth):
// accuracy, no tracking loss, a pose for every frame (the frames the map's
// start waited on get theirs when it starts), and bit-for-bit repeatability
// in deterministic mode.
#include <gtest/gtest.h>

#include <algorithm>

#include "stillslam/eval/evaluate.h"
#include "stillslam/system/system.h"
#include "system/corner_person.h"
#include "system/sim_sequence.h"

namespace stillslam {
namespace {

struct RunOutput {
  Trajectory trajectory;
  // Per frame, the frames posed at the start marked as DatasetRunner marks them.
  std::vector<FrameStats> frames;
  int tracked = 0, lost = 0, keyframes = 0;
};

RunOutput run(const test::SimSequence& seq, SensorType sensor, bool deterministic = true) {
  SystemOptions options;
  options.deterministic = deterministic;
  Settings settings = seq.settings;
  settings.tracking.init_min_keypoints = 300;
  System system(settings, sensor, seq.stereo, options);
  RunOutput out;
  for (const SensorFrame& f : seq.frames) {
    FrameStats stats = system.process(f);
    mark_start_frames_posed(out.frames, stats);
    out.frames.push_back(std::move(stats));
  }
  for (const FrameStats& stats : out.frames) {
    out.tracked += stats.has_pose ? 1 : 0;
    out.lost += stats.state == TrackingState::Lost ? 1 : 0;
    out.keyframes += stats.keyframe ? 1 : 0;
  }
  system.shutdown();
  out.trajectory = system.trajectory();
  return out;
}

const test::SimSequence& rgbd_sequence() {
  static const test::SimSequence seq = test::render_sim_sequence("walking_xyz", 90, 320, 240, false);
  return seq;
}

// Without segmentation the map starts at frame 3 from frame 0 (the start
// check, Tracking.initUnmaskedConfirmFrames 3): frames 0-2 get their poses then.
void expect_started_at_frame_3(const RunOutput& out) {
  ASSERT_GT(out.frames.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(out.frames[k].state, TrackingState::NotInitialized) << k;
    EXPECT_TRUE(out.frames[k].has_pose) << k;
    EXPECT_TRUE(out.frames[k].posed_at_start) << k;
  }
  EXPECT_EQ(out.frames[3].state, TrackingState::Ok);
  EXPECT_NE(out.frames[3].reason.find("map started at frame 0"), std::string::npos) << out.frames[3].reason;
  ASSERT_EQ(out.frames[3].start_frames_posed.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(out.frames[3].start_frames_posed[k].index, out.frames[k].index);
  EXPECT_FALSE(out.frames[3].posed_at_start);
}

TEST(SystemEndToEnd, RgbdSyntheticSequenceIsTrackedAccurately) {
  const test::SimSequence& seq = rgbd_sequence();
  const RunOutput out = run(seq, SensorType::Rgbd);
  expect_started_at_frame_3(out);
  EXPECT_EQ(out.tracked, static_cast<int>(seq.frames.size()));
  EXPECT_EQ(out.lost, 0);
  EXPECT_GE(out.keyframes, 2);
  const EvaluationResult ev = evaluate(seq.groundtruth, out.trajectory, EvaluationOptions{});
  EXPECT_EQ(ev.pairs, seq.frames.size());
  std::cout << "RGB-D synthetic ATE rmse " << ev.ape_stats.rmse << " m, keyframes " << out.keyframes << "\n";
  EXPECT_LT(ev.ape_stats.rmse, 0.01);
}

TEST(SystemEndToEnd, DeterministicModeRepeatsBitForBit) {
  const test::SimSequence& seq = rgbd_sequence();
  const RunOutput a = run(seq, SensorType::Rgbd);
  const RunOutput b = run(seq, SensorType::Rgbd);
  ASSERT_EQ(a.trajectory.size(), seq.frames.size());
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (std::size_t i = 0; i < a.trajectory.size(); ++i) {
    EXPECT_EQ(a.trajectory[i].timestamp, b.trajectory[i].timestamp);
    EXPECT_TRUE(a.trajectory[i].T_world_cam.matrix() == b.trajectory[i].T_world_cam.matrix()) << "frame " << i;
  }
}

TEST(SystemEndToEnd, ConcurrentLocalMappingTracksAccurately) {
  // Local mapping on its own thread (BA aborts, map lock shared with tracking).
  const test::SimSequence& seq = rgbd_sequence();
  const RunOutput out = run(seq, SensorType::Rgbd, false);
  expect_started_at_frame_3(out);
  EXPECT_EQ(out.tracked, static_cast<int>(seq.frames.size()));
  EXPECT_EQ(out.lost, 0);
  const EvaluationResult ev = evaluate(seq.groundtruth, out.trajectory, EvaluationOptions{});
  std::cout << "RGB-D synthetic, concurrent mapping: ATE rmse " << ev.ape_stats.rmse << " m\n";
  EXPECT_LT(ev.ape_stats.rmse, 0.015);
}

TEST(SystemEndToEnd, StereoSyntheticSequenceIsTrackedAccurately) {
  const test::SimSequence seq = test::render_sim_sequence("walking_xyz", 60, 320, 240, true);
  const RunOutput out = run(seq, SensorType::Stereo);
  expect_started_at_frame_3(out);
  EXPECT_EQ(out.tracked, static_cast<int>(seq.frames.size()));
  EXPECT_EQ(out.lost, 0);
  const EvaluationResult ev = evaluate(seq.groundtruth, out.trajectory, EvaluationOptions{});
  std::cout << "stereo synthetic ATE rmse " << ev.ape_stats.rmse << " m\n";
  EXPECT_LT(ev.ape_stats.rmse, 0.015);
}

// A segmenter that always finds one person on the left half of the frame.
class LeftHalfPerson : public Segmenter {
 public:
  explicit LeftHalfPerson(int* calls) : calls_(calls) {}
  std::vector<Detection> segment(const cv::Mat& bgr) override {
    ++*calls_;
    Detection d;
    d.class_id = 0;
    d.class_name = "person";
    d.score = 0.9f;
    d.box = cv::Rect2f(0, 0, bgr.cols / 2.f, static_cast<float>(bgr.rows));
    d.mask = cv::Mat1b::zeros(bgr.size());
    d.mask(cv::Rect(0, 0, bgr.cols / 2, bgr.rows)).setTo(255);
    return {d};
  }

 private:
  int* calls_;
};

TEST(SystemEndToEnd, SegmenterFactoryReplacesTheModel) {
  test::SimSequence seq = rgbd_sequence();
  seq.settings.segmentation.enabled = true;
  seq.settings.segmentation.mask_dilation = 0;
  seq.settings.segmentation.model_path = "/nonexistent/model.onnx";  // never opened
  int calls = 0;
  SystemOptions options;
  options.deterministic = true;
  seq.settings.tracking.init_min_keypoints = 300;
  options.segmenter_factory = [&calls] { return std::make_unique<LeftHalfPerson>(&calls); };
  System system(seq.settings, SensorType::Rgbd, seq.stereo, options);
  for (int i = 0; i < 5; ++i) {
    const FrameStats stats = system.process(seq.frames[i]);
    EXPECT_EQ(stats.build.detections, 1);
    EXPECT_NEAR(stats.build.mask_coverage, 0.5, 1e-9);
    EXPECT_GT(stats.build.keypoints_after, 500);  // the whole budget on the right half
  }
  system.shutdown();
  EXPECT_EQ(calls, 5);
}

// Every third frame of a sequence (as --realtime drops frames while the
// system is busy): the camera moves 15-20 mm between the frames processed at
// the start of walking_xyz, several times the pose error. Frames keep their
// input index (the ground truth's).
test::SimSequence every_third(const test::SimSequence& seq) {
  test::SimSequence out = seq;
  out.frames.clear();
  for (std::size_t i = 0; i < seq.frames.size(); i += 3) out.frames.push_back(seq.frames[i]);
  return out;
}

// The frames the start waited on against the ground truth, in the map's
// frame (the first waited frame's camera, no alignment).
struct StartPoses {
  std::size_t waited = 0;               // frames posed at the start
  double max_error_m = 1e9;             // their worst position error as posed at the start (FrameStats)
  double max_angle_rad = 1e9;
  double max_trajectory_error_m = 1e9;  // the same in the trajectory (refined against the final map)
  double min_motion_m = 0;              // the least ground-truth motion from the first frame among them
  double max_tracked_error_m = 1e9;     // max_trajectory_error_m's measure over the 8 frames after them
};

StartPoses start_poses(const test::SimSequence& seq, const RunOutput& out) {
  StartPoses p;
  std::size_t start = 0;
  while (start < out.frames.size() && out.frames[start].start_frames_posed.empty()) ++start;
  if (start == out.frames.size()) return p;
  const std::vector<FrameStats::EarlierPose>& posed = out.frames[start].start_frames_posed;
  p.waited = posed.size();
  const Eigen::Isometry3d gt_first = seq.groundtruth[posed.front().index].T_world_cam;
  auto gt_of = [&](std::size_t index) { return gt_first.inverse() * seq.groundtruth[index].T_world_cam; };
  auto trajectory_error = [&](std::size_t index, double timestamp) {
    double e = 1e9;  // not in the trajectory
    for (const StampedPose& t : out.trajectory) {
      if (t.timestamp == timestamp) e = (t.T_world_cam.translation() - gt_of(index).translation()).norm();
    }
    return e;
  };
  p.max_error_m = p.max_angle_rad = p.max_trajectory_error_m = p.max_tracked_error_m = 0;
  p.min_motion_m = 1e9;
  for (const FrameStats::EarlierPose& e : posed) {
    const Eigen::Isometry3d d = e.T_world_cam.inverse() * gt_of(e.index);
    p.max_error_m = std::max(p.max_error_m, d.translation().norm());
    p.max_angle_rad = std::max(p.max_angle_rad, Eigen::AngleAxisd(d.linear()).angle());
    p.max_trajectory_error_m = std::max(p.max_trajectory_error_m, trajectory_error(e.index, e.timestamp));
    if (e.index != posed.front().index) p.min_motion_m = std::min(p.min_motion_m, gt_of(e.index).translation().norm());
  }
  for (std::size_t i = start; i < start + 8 && i < out.frames.size(); ++i) {
    p.max_tracked_error_m = std::max(p.max_tracked_error_m, trajectory_error(out.frames[i].index, out.frames[i].timestamp));
  }
  return p;
}

// mm-level (the 320x240 renders put the tracked frames 6-9 mm from the
// ground truth in this unaligned measure): as posed at the start within 7 mm
// and 3 mrad, in the trajectory within 8 mm and no worse than the 8 frames
// tracked after them (+1 mm), while each moved at least 15 mm from the first
// (a pose left there would fail).
void expect_start_poses(const StartPoses& p, std::size_t waited, const char* what) {
  std::cout << what << ": " << p.waited << " frames posed at the start, within " << 1000 * p.max_error_m << " mm and "
            << 1000 * p.max_angle_rad << " mrad, in the trajectory " << 1000 * p.max_trajectory_error_m
            << " mm (the 8 frames after: " << 1000 * p.max_tracked_error_m << " mm); motion >= "
            << 1000 * p.min_motion_m << " mm\n";
  EXPECT_EQ(p.waited, waited) << what;
  EXPECT_GT(p.min_motion_m, 0.015) << what;
  EXPECT_LT(p.max_error_m, 0.007) << what;
  EXPECT_LT(p.max_angle_rad, 0.003) << what;
  EXPECT_LT(p.max_trajectory_error_m, 0.008) << what;
  EXPECT_LT(p.max_trajectory_error_m, p.max_tracked_error_m + 0.001) << what;
}

TEST(SystemEndToEnd, TheFramesTheStartWaitedOnArePosedAtTheirGroundTruth) {
  // Without segmentation, RGB-D and stereo: frames 0-2 wait on the start check.
  const test::SimSequence rgbd = every_third(rgbd_sequence());
  const RunOutput unmasked = run(rgbd, SensorType::Rgbd);
  expect_started_at_frame_3(unmasked);
  EXPECT_EQ(unmasked.trajectory.size(), rgbd.frames.size());
  expect_start_poses(start_poses(rgbd, unmasked), 3, "RGB-D without masks");

  const test::SimSequence stereo = every_third(test::render_sim_sequence("walking_xyz", 36, 320, 240, true));
  const RunOutput unmasked_stereo = run(stereo, SensorType::Stereo);
  expect_started_at_frame_3(unmasked_stereo);
  EXPECT_EQ(unmasked_stereo.tracked, static_cast<int>(stereo.frames.size()));
  EXPECT_EQ(unmasked_stereo.trajectory.size(), stereo.frames.size());
  expect_start_poses(start_poses(stereo, unmasked_stereo), 3, "stereo without masks");

  // With segmentation on: frames 0-1 wait on the check with masks (Tracking.initConfirmFrames 2).
  test::SimSequence segmented = rgbd;
  segmented.settings.segmentation.enabled = true;
  segmented.settings.segmentation.mask_dilation = 0;
  segmented.settings.segmentation.model_path = "/nonexistent/model.onnx";  // never opened
  segmented.settings.tracking.init_min_keypoints = 300;
  SystemOptions options;
  options.deterministic = true;
  options.segmenter_factory = [] { return std::make_unique<test::CornerPerson>(); };
  System system(segmented.settings, SensorType::Rgbd, segmented.stereo, options);
  RunOutput masked;
  for (const SensorFrame& f : segmented.frames) {
    FrameStats stats = system.process(f);
    mark_start_frames_posed(masked.frames, stats);
    masked.frames.push_back(std::move(stats));
  }
  system.shutdown();
  masked.trajectory = system.trajectory();
  ASSERT_GT(masked.frames.size(), 2u);
  EXPECT_EQ(masked.frames[2].reason.rfind("map started at frame 0, confirmed by 2 frames", 0), 0u)
      << masked.frames[2].reason;
  for (const FrameStats& f : masked.frames) EXPECT_TRUE(f.has_pose) << f.index;
  EXPECT_EQ(masked.trajectory.size(), segmented.frames.size());
  expect_start_poses(start_poses(segmented, masked), 2, "RGB-D with masks");
}

}  // namespace
}  // namespace stillslam
