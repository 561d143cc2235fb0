// The loop-closing bar end to end: a rendered turn around the room with
// sensor noise (odometry drifts), run through the whole System with the
// committed vocabulary, with loop closing on and off (deterministic mode).
// The loop must be detected when the camera is back at the start, and the
// corrected trajectory must have at most half the ATE of the uncorrected one.
#include <gtest/gtest.h>

#include <iostream>

#include "loop/rendered_loop.h"

namespace stillslam {
namespace {

TEST(LoopClosingEndToEnd, RenderedLoopIsClosedAndHalvesTheError) {
  if (!std::filesystem::exists(test::committed_vocabulary())) GTEST_SKIP() << "no " << test::committed_vocabulary();
  const test::RenderedLoopOptions options;
  const test::RenderedLoop seq = test::render_loop(options);
  ASSERT_EQ(seq.frames.size(), 230u);
  const auto turn = static_cast<std::size_t>(sim::CameraMotion::kLoopPeriod * options.fps);  // frame = start pose again

  test::LoopRunOptions off_options;
  off_options.loop_closing = false;
  const test::LoopRun off = test::run_loop(seq.settings, seq.frames, off_options);
  const test::LoopRun on = test::run_loop(seq.settings, seq.frames, {});
  for (const test::LoopRun* r : {&off, &on}) {
    for (const FrameStats& f : r->frames) ASSERT_TRUE(f.has_pose) << "frame " << f.index << " not tracked";
  }
  const double ate_off = test::ate_rmse(seq.groundtruth, off.trajectory);
  const double ate_on = test::ate_rmse(seq.groundtruth, on.trajectory);
  const double end_off = test::error_at(seq.groundtruth, off.trajectory, turn).value_or(-1);
  const double end_on = test::error_at(seq.groundtruth, on.trajectory, turn).value_or(-1);
  std::cout << "ATE rmse without loop closing " << ate_off << " m, with " << ate_on << " m (ratio "
            << ate_on / ate_off << "); error back at the start " << end_off << " -> " << end_on << " m; loops "
            << on.loop_closer.loops_closed << " closed at frame " << (on.closed_at.empty() ? -1 : int(on.closed_at[0]))
            << "; keyframes " << on.loop_closer.keyframes << "; global BA " << on.loop_closer.global_bundle_adjustments
            << "\n";

  EXPECT_EQ(off.loop_closer.loops_closed, 0);
  ASSERT_GE(on.loop_closer.loops_closed, 1);
  // Closed after the camera is back at the start (not a false loop on the way round) ...
  EXPECT_GE(on.closed_at.front(), turn - 20);
  EXPECT_EQ(on.loop_closer.global_bundle_adjustments, on.loop_closer.loops_closed);
  // ... on a sequence that drifts enough for the bar to mean something ...
  EXPECT_GT(ate_off, 0.01);
  EXPECT_GT(end_off, 0.02);
  // ... and the correction reaches the trajectory output.
  EXPECT_LE(ate_on, 0.5 * ate_off);
  EXPECT_LE(end_on, 0.5 * end_off);
}

}  // namespace
}  // namespace stillslam
