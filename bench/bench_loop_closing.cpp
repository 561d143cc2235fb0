// The loop-closing bar (issue #6): the simulator's "loop" path (one turn
// around the room in 20 s, then on past the start) with sensor noise so that
// odometry drifts, run through the whole System with loop closing on and off.
// Prints ATE rmse of both, their ratio (bar: <= 0.5), loops closed and the
// frame where it happened, and the drift back at the start pose.
//
//   build/bench/bench_loop_closing [--sequence DIR] [--threaded] [--runs N]
//       [--frames N] [--fps F] [--width W] [--height H] [--noise L] [--seed S] [--features N]
//       [--vocabulary FILE] [--no-global-ba] [--trajectories DIR] [--verbose: every frame, loop detector decisions]
//
// Without --sequence the sequence is rendered in memory (defaults: the
// end-to-end test's 230 frames at 10 Hz, 320x240, noise 1, 1000 features).
// --sequence reads a folder written by
//   stillslam simulate --out DIR --trajectory loop --frames 700 --no-people --noise 1
// with its settings.yaml and groundtruth.txt (--features overrides nFeatures).
// Default mode is deterministic (synchronous local mapping and loop closing:
// same input, same numbers); --threaded runs the threads as `stillslam run`
// does (numbers vary from run to run; --runs N repeats each mode).
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "../tests/loop/rendered_loop.h"
#include "stillslam/core/error.h"
#include "stillslam/io/dataset.h"
#include "stillslam/settings/settings.h"

using namespace stillslam;

namespace {

struct Args {
  std::string sequence, trajectories;
  test::RenderedLoopOptions render;
  int features = 0;  // 0: the sequence's (or the render default)
  bool threaded = false, verbose = false, global_ba = true;
  int runs = 1;
  std::filesystem::path vocabulary = test::committed_vocabulary();
};

Args parse(int argc, char** argv) {
  Args a;
  CLI::App app("Loop-closing bar (see the comment at the top of bench/bench_loop_closing.cpp)", "bench_loop_closing");
  app.add_option("--sequence", a.sequence, "TUM folder instead of rendering");
  app.add_option("--trajectories", a.trajectories, "write the estimated trajectories into this folder");
  app.add_option("--frames", a.render.frames, "rendered frames")->capture_default_str();
  app.add_option("--fps", a.render.fps, "rendered frame rate")->capture_default_str();
  app.add_option("--width", a.render.width, "rendered width")->capture_default_str();
  app.add_option("--height", a.render.height, "rendered height")->capture_default_str();
  app.add_option("--noise", a.render.noise, "sensor noise level")->capture_default_str();
  app.add_option("--seed", a.render.seed, "render seed")->capture_default_str();
  app.add_option("--features", a.features, "ORB features (0: the sequence's or the render default)")
      ->capture_default_str();
  app.add_option("--runs", a.runs, "repeat each mode N times (at least 1)")->capture_default_str();
  app.add_option("--vocabulary", a.vocabulary, "ORB vocabulary file")->capture_default_str();
  app.add_flag("--threaded", a.threaded, "threads as in `stillslam run`");
  bool no_global_ba = false;
  app.add_flag("--no-global-ba", no_global_ba, "no global BA after a loop closure");
  app.add_flag("--verbose", a.verbose, "every frame, loop detector decisions");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::exit(app.exit(e));  // --help prints and exits 0; bad values print CLI11's message and exit non-zero
  }
  a.global_ba = !no_global_ba;
  a.runs = std::max(1, a.runs);
  if (a.features > 0) a.render.features = a.features;
  return a;
}

test::RenderedLoop load_sequence(const Args& a) {
  if (a.sequence.empty()) return test::render_loop(a.render);
  const std::filesystem::path dir(a.sequence);
  test::RenderedLoop out;
  out.settings = load_settings(dir / "settings.yaml");
  out.settings.segmentation.enabled = false;
  if (a.features > 0) out.settings.orb.n_features = a.features;
  const auto dataset = open_dataset(dir, out.settings);
  for (std::size_t i = 0; i < dataset->size(); ++i) out.frames.push_back(dataset->load(i));
  out.groundtruth = read_trajectory(dir / "groundtruth.txt");
  return out;
}

// Ground truth at the frames' timestamps (files may hold more poses).
Trajectory groundtruth_at_frames(const test::RenderedLoop& seq) {
  Trajectory out;
  for (const SensorFrame& f : seq.frames) {
    for (const StampedPose& g : seq.groundtruth) {
      if (std::abs(g.timestamp - f.timestamp) < 1e-4) {
        out.push_back(g);
        break;
      }
    }
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args args = parse(argc, argv);
    if (args.verbose) spdlog::set_level(spdlog::level::debug);  // the loop detector's decisions
    Stopwatch load_time;
    const test::RenderedLoop seq = load_sequence(args);
    const Trajectory gt = groundtruth_at_frames(seq);
    const double fps = seq.settings.fps > 0 ? seq.settings.fps : args.render.fps;
    const auto turn = static_cast<std::size_t>(std::lround(sim::CameraMotion::kLoopPeriod * fps));
    std::printf("sequence: %s, %zu frames %dx%d at %.0f Hz (start pose again at frame %zu), %d features, %s; "
                "loaded in %.1f s\n",
                args.sequence.empty() ? "rendered in memory" : args.sequence.c_str(), seq.frames.size(),
                seq.settings.camera.width, seq.settings.camera.height, fps, turn, seq.settings.orb.n_features,
                args.threaded ? "threaded" : "deterministic", load_time.elapsed_ms() / 1000.0);
    std::printf("%-4s %-4s %10s %12s %8s %7s %10s %10s %6s %8s %8s\n", "mode", "run", "ATE rmse", "err@start", "tracked",
                "loops", "closed at", "GBA done", "KFs", "corr ms", "wall s");
    std::vector<double> ratios;
    for (int run = 0; run < args.runs; ++run) {
      double ate[2] = {0, 0};
      for (int on = 0; on < 2; ++on) {
        test::LoopRunOptions o;
        o.loop_closing = on == 1;
        o.deterministic = !args.threaded;
        o.vocabulary = args.vocabulary;
        o.global_bundle_adjustment = args.global_ba;
        const test::LoopRun r = test::run_loop(seq.settings, seq.frames, o);
        int tracked = 0;
        for (const FrameStats& f : r.frames) tracked += f.has_pose ? 1 : 0;
        ate[on] = test::ate_rmse(gt, r.trajectory);
        const auto end = test::error_at(gt, r.trajectory, turn);
        std::string closed_at;
        for (std::size_t f : r.closed_at) closed_at += (closed_at.empty() ? "" : ",") + std::to_string(f);
        std::printf("%-4s %-4d %10.4f %12.4f %8d %7d %10s %4d/%-4d %6d %8.0f %8.1f\n", on ? "on" : "off", run, ate[on],
                    end.value_or(-1), tracked, r.loop_closer.loops_closed, closed_at.empty() ? "-" : closed_at.c_str(),
                    r.loop_closer.global_bundle_adjustments - r.loop_closer.global_bundle_adjustments_aborted,
                    r.loop_closer.global_bundle_adjustments, r.loop_closer.keyframes, r.loop_closer.correction_ms,
                    r.seconds);
        if (args.verbose) {
          for (const FrameStats& f : r.frames) {
            const auto e = test::error_at(gt, r.trajectory, f.index);
            std::printf("  frame %4zu %-8s %-22s matches %4d inliers %4d kf %d err %.4f\n", f.index, to_string(f.state),
                        f.reason.c_str(), f.matches, f.inliers, f.keyframe ? 1 : 0, e.value_or(-1));
          }
        }
        if (!args.trajectories.empty()) {
          std::filesystem::create_directories(args.trajectories);
          write_trajectory(std::filesystem::path(args.trajectories) /
                               ("run" + std::to_string(run) + (on ? "_on" : "_off") + ".txt"),
                           r.trajectory);
        }
      }
      ratios.push_back(ate[1] / ate[0]);
      std::printf("run %d: ATE with / without loop closing = %.3f (bar: <= 0.5)\n", run, ratios.back());
    }
    if (args.runs > 1) {
      std::sort(ratios.begin(), ratios.end());
      std::printf("ratio over %d runs: min %.3f median %.3f max %.3f\n", args.runs, ratios.front(),
                  ratios[ratios.size() / 2], ratios.back());
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_loop_closing: %s\n", e.what());
    return 1;
  }
}
