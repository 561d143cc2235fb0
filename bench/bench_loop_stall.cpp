// How long loop closing holds the map lock per keyframe on the synthetic
// drift loop of tests/loop (loop_scene.h: 42 keyframes on a circle, 3000
// points; fed one keyframe at a time the loop is verified at keyframe 33),
// today's detect() against the split
// prepare() (lock) + verify() (no lock) + recheck() (lock), and the lock-held
// steps after a detection: correct_loop() (essential graph; also split into
// begin (lock) / solve (no lock) / finish (lock), measured on a second copy
// of the scene) and the global BA's snapshot / apply (its solve runs without
// the lock).
//
//   build/bench/bench_loop_stall [--repeats N] [--points N]
//
// Each repeat builds the scene anew and feeds keyframes 0, 1, ... as the loop
// closer does (add keyframe, detect, index). Figures are medians over the
// repeats of per-call times: wall clock and CPU time of the calling thread
// (the latter unaffected by other processes on the cores). "per keyframe" is
// the median over keyframes 11 to the one before the loop; "loop keyframe" is
// the one where verification succeeds; "longest of all keyframes" the
// median over repeats of each run's longest hold (CPU).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "../tests/loop/loop_scene.h"  // same scene as the tests
#include "stillslam/core/stopwatch.h"
#include "stillslam/loop/global_bundle_adjustment.h"
#include "stillslam/loop/loop_closer_options.h"
#include "stillslam/loop/loop_correction.h"
#include "stillslam/loop/loop_detector.h"
#include "stillslam/loop/place_recognizer.h"
#include "stillslam/core/thread_cpu_stopwatch.h"

using namespace stillslam;

namespace {

struct Cost {
  double wall = 0, cpu = 0;
  Cost& operator+=(const Cost& o) {
    wall += o.wall;
    cpu += o.cpu;
    return *this;
  }
};

template <typename F>
Cost timed(F&& f) {
  Stopwatch w;
  ThreadCpuStopwatch cpu;
  f();
  return {w.elapsed_ms(), cpu.elapsed_ms()};
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Per operation: one Cost per repeat (and per keyframe where it applies).
struct Samples {
  std::vector<double> wall, cpu;
  void add(const Cost& c) {
    wall.push_back(c.wall);
    cpu.push_back(c.cpu);
  }
};

void row(const char* name, const Samples& s, const char* lock) {
  std::printf("%-46s %-8s %6zu %9.3f %9.3f\n", name, lock, s.wall.size(), median(s.wall), median(s.cpu));
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 7;
  int points = 3000;
  CLI::App app("Map-lock hold times of loop closing (see the comment at the top of bench/bench_loop_stall.cpp)",
               "bench_loop_stall");
  app.add_option("--repeats", repeats, "scenes built and run (at least 1)")->capture_default_str();
  app.add_option("--points", points, "points on the cylinder wall (the tests use 3000)")->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  repeats = std::max(1, repeats);
  test::LoopScene::Options scene_options;
  scene_options.num_points = std::max(100, points);
  const auto vocabulary = std::make_shared<const Vocabulary>(test::LoopScene(scene_options).train_vocabulary());

  // Per keyframe before the loop (pooled over keyframes 11-31 and repeats).
  Samples detect_kf, prepare_kf, verify_kf, add_kf;
  // At the loop keyframe.
  Samples describe_loop, copy_loop;  // parts of prepare()
  Samples detect_loop, prepare_loop, verify_loop, recheck_loop, lock_split_loop;
  Samples correct, correct_begin, correct_solve, correct_finish, gba_snapshot, gba_solve, gba_apply;
  std::vector<double> worst_today_all, worst_split_all;  // per repeat: longest hold over the keyframes
  std::size_t snapshot_points = 0, snapshot_candidates = 0, graph_nodes = 0;
  int loop_at = -1;
  for (int r = 0; r < repeats; ++r) {
    test::LoopScene scene(scene_options);
    PlaceRecognizer recognizer(vocabulary);
    LoopDetector today(recognizer), split(recognizer);
    std::optional<LoopDetection> detection;
    double worst_today = 0, worst_split = 0;  // cpu ms
    for (int i = 0; i < 42 && !detection; ++i) {
      const KeyFramePtr kf = scene.add_keyframe(i);
      std::optional<LoopDetection> expected;
      const Cost c_detect = timed([&] { expected = today.detect(scene.map(), *kf); });
      std::optional<LoopSnapshot> snapshot;
      const Cost c_prepare = timed([&] { snapshot = split.prepare(scene.map(), *kf); });
      Cost c_verify, c_recheck;
      if (snapshot) c_verify = timed([&] { detection = split.verify(*snapshot); });
      if (detection) c_recheck = timed([&] { detection = split.recheck(scene.map(), *detection); });
      const Cost c_add = timed([&] { recognizer.add(*kf); });
      Cost held = c_prepare;
      held += c_recheck;
      worst_today = std::max(worst_today, c_detect.cpu);
      worst_split = std::max(worst_split, held.cpu);
      if (expected.has_value() != detection.has_value() ||
          (expected && (expected->loop != detection->loop || expected->inliers != detection->inliers))) {
        std::fprintf(stderr, "keyframe %d: detect() and prepare/verify/recheck disagree\n", i);
        return 1;
      }
      if (detection) {
        loop_at = i;
        detect_loop.add(c_detect);
        prepare_loop.add(c_prepare);
        verify_loop.add(c_verify);
        recheck_loop.add(c_recheck);
        lock_split_loop.add(held);
        describe_loop.add(timed([&] { recognizer.describe(PlaceRecognizer::descriptors_of(*kf)); }));
        copy_loop.add(timed([&] {
          LoopSnapshotBuilder builder(*kf, snapshot->query_words, 10);
          for (const LoopCandidateCopy& c : snapshot->candidates) {
            builder.add_candidate(c.keyframe.keyframe, c.words, c.needs_confirmation, c.needed_confirmations);
          }
          builder.take();
        }));
        snapshot_points = snapshot->points.size();
        snapshot_candidates = snapshot->candidates.size();
      } else if (i >= 11) {
        detect_kf.add(c_detect);
        prepare_kf.add(c_prepare);
        if (snapshot) verify_kf.add(c_verify);
        add_kf.add(c_add);
      }
    }
    if (!detection) {
      std::fprintf(stderr, "no loop detected\n");
      return 1;
    }
    worst_today_all.push_back(worst_today);
    worst_split_all.push_back(worst_split);
    LoopEdges edges;
    LoopCorrectionStats stats;
    correct.add(timed([&] { stats = correct_loop(scene.map(), *detection, edges); }));
    graph_nodes = static_cast<std::size_t>(stats.graph_nodes);
    {
      // The same closure in three steps, on a second copy of the scene.
      test::LoopScene scene2(scene_options);
      PlaceRecognizer recognizer2(vocabulary);
      LoopDetector detector2(recognizer2);
      std::optional<LoopDetection> detection2;
      for (int i = 0; i < 42 && !detection2; ++i) {
        const KeyFramePtr kf = scene2.add_keyframe(i);
        detection2 = detector2.detect(scene2.map(), *kf);
        recognizer2.add(*kf);
      }
      LoopEdges edges2;
      LoopCorrectionProblem correction;
      std::vector<Eigen::Isometry3d> solved;
      correct_begin.add(timed([&] { correction = begin_loop_correction(scene2.map(), *detection2, edges2); }));
      correct_solve.add(timed([&] { solved = solve_loop_correction(correction); }));
      correct_finish.add(timed([&] { finish_loop_correction(scene2.map(), correction, solved, edges2); }));
    }
    GlobalBundleAdjustmentProblem problem;
    gba_snapshot.add(timed([&] { problem = snapshot_global_problem(scene.map()); }));
    BundleAdjustmentResult result;
    gba_solve.add(timed([&] {
      result = solve_global_problem(problem, LoopCloserOptions::default_global_bundle_adjustment());
    }));
    gba_apply.add(timed([&] { apply_global_result(scene.map(), problem, result); }));
  }

  std::printf("scene: %d points, loop verified at keyframe %d, %d repeats; snapshot there: %zu candidates, %zu "
              "points; essential graph %zu keyframes\n",
              scene_options.num_points, loop_at, repeats, snapshot_candidates, snapshot_points, graph_nodes);
  std::printf("%-46s %-8s %6s %9s %9s\n", "operation", "lock", "calls", "wall ms", "cpu ms");
  row("per keyframe: detect() (as today)", detect_kf, "held");
  row("per keyframe: prepare()", prepare_kf, "held");
  row("per keyframe: verify() (when prepared)", verify_kf, "free");
  row("per keyframe: recognizer add (describe+index)", add_kf, "held*");
  row("loop keyframe: detect() (as today)", detect_loop, "held");
  row("loop keyframe: prepare()", prepare_loop, "held");
  row("  of which: BoW description of the query", describe_loop, "held");
  row("  of which: copies (LoopSnapshotBuilder)", copy_loop, "held");
  row("loop keyframe: verify()", verify_loop, "free");
  row("loop keyframe: recheck()", recheck_loop, "held");
  row("loop keyframe: prepare() + recheck()", lock_split_loop, "held");
  std::printf("%-46s %-8s %6zu %9s %9.3f\n", "longest of all keyframes: detect() (as today)", "held", worst_today_all.size(),
              "", median(worst_today_all));
  std::printf("%-46s %-8s %6zu %9s %9.3f\n", "longest of all keyframes: prepare() + recheck()", "held",
              worst_split_all.size(), "", median(worst_split_all));
  row("correct_loop() (essential graph)", correct, "held");
  row("  split: begin_loop_correction()", correct_begin, "held");
  row("  split: solve_loop_correction()", correct_solve, "free");
  row("  split: finish_loop_correction()", correct_finish, "held");
  row("global BA: snapshot", gba_snapshot, "held");
  row("global BA: solve", gba_solve, "free");
  row("global BA: apply_global_result()", gba_apply, "held");
  std::printf("* LoopCloser indexes the keyframe under the lock today; it reads only descriptors, so it need not.\n");
  return 0;
}
