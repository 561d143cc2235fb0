// End to end on short synthetic sequences (static scene, exact ground truth):
// accuracy, no tracking loss, and bit-for-bit repeatability in deterministic mode.
#include <gtest/gtest.h>

#include "stillslam/eval/evaluate.h"
#include "stillslam/system/system.h"
#include "system/sim_sequence.h"

namespace stillslam {
namespace {

struct RunOutput {
  Trajectory trajectory;
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
    const FrameStats stats = system.process(f);
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

TEST(SystemEndToEnd, RgbdSyntheticSequenceIsTrackedAccurately) {
  const test::SimSequence& seq = rgbd_sequence();
  const RunOutput out = run(seq, SensorType::Rgbd);
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
  EXPECT_EQ(out.tracked, static_cast<int>(seq.frames.size()));
  EXPECT_EQ(out.lost, 0);
  const EvaluationResult ev = evaluate(seq.groundtruth, out.trajectory, EvaluationOptions{});
  std::cout << "RGB-D synthetic, concurrent mapping: ATE rmse " << ev.ape_stats.rmse << " m\n";
  EXPECT_LT(ev.ape_stats.rmse, 0.015);
}

TEST(SystemEndToEnd, StereoSyntheticSequenceIsTrackedAccurately) {
  const test::SimSequence seq = test::render_sim_sequence("walking_xyz", 60, 320, 240, true);
  const RunOutput out = run(seq, SensorType::Stereo);
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

}  // namespace
}  // namespace stillslam
