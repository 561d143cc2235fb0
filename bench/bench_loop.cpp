// Place recognition, relocalization and loop closing timings on the synthetic
// drift loop of tests/loop (random descriptors on a cylinder wall, keyframes
// on a circle, exact measurements, odometry bias of 8 degrees per turn).
// Plain main (prints a table), so it runs with or without Google Benchmark.
//
//   build/bench/bench_loop [--turns N] [--repeats N]
//
// Times are per call: wall clock and CPU time of the calling thread (the
// latter is unaffected by other processes competing for the cores).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "../tests/loop/loop_scene.h"  // same scene as the tests
#include "../tests/loop/real_place_data.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/core/thread_cpu_stopwatch.h"
#include "stillslam/loop/loop_closer.h"
#include "stillslam/loop/loop_detector.h"
#include "stillslam/loop/place_recognizer.h"
#include "stillslam/tracking/relocalizer.h"

using namespace stillslam;

namespace {

struct Timing {
  std::vector<double> wall, cpu;
  void add(double w, double c) {
    wall.push_back(w);
    cpu.push_back(c);
  }
};

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

void row(const char* name, const Timing& t, const char* note = "") {
  std::printf("%-44s %6zu %10.3f %10.3f  %s\n", name, t.wall.size(), median(t.wall), median(t.cpu), note);
}

template <typename F>
void timed(Timing& t, F&& f) {
  Stopwatch w;
  const ThreadCpuStopwatch cpu_watch;
  f();
  t.add(w.elapsed_ms(), cpu_watch.elapsed_ms());
}

}  // namespace

int main(int argc, char** argv) {
  int turns = 1;
  int repeats = 20;
  CLI::App app("Loop detection and closing costs (see the comment at the top of bench/bench_loop.cpp)", "bench_loop");
  app.add_option("--turns", turns, "turns around the scene (36 keyframes each, at least 1)")->capture_default_str();
  app.add_option("--repeats", repeats, "calls per timed operation (at least 1)")->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);  // --help prints and exits 0; bad values print CLI11's message and exit non-zero
  }
  turns = std::max(1, turns);
  repeats = std::max(1, repeats);
  const int keyframes = 36 * turns;
  test::LoopScene scene;
  auto vocabulary = std::make_shared<const Vocabulary>(scene.train_vocabulary());
  std::printf("vocabulary: %zu words, k=%d, depth %d\n", vocabulary->size(), vocabulary->k(), vocabulary->depth());
  std::printf("%-44s %6s %10s %10s\n", "operation", "calls", "wall ms", "cpu ms");

  // Map without detection: keyframes indexed one by one, loop query per keyframe.
  PlaceRecognizer recognizer(vocabulary);
  LoopDetectorOptions detector_options;
  detector_options.consistency_threshold = 1000;  // measure candidate search, never verify
  LoopDetector detector(recognizer, detector_options);
  Timing add, query, candidates;
  std::vector<KeyFramePtr> kfs;
  for (int i = 0; i < keyframes; ++i) {
    kfs.push_back(scene.add_keyframe(i));
  }
  for (const auto& kf : kfs) {
    std::vector<KeyframeId> covisible;
    for (KeyFrame* k : kf->covisibles()) covisible.push_back(k->id());
    timed(query, [&] { recognizer.loop_candidates(*kf, covisible); });
    timed(candidates, [&] { detector.detect(scene.map(), *kf); });
    timed(add, [&] { recognizer.add(*kf); });
  }
  row("place: describe + index keyframe", add);
  row("place: loop candidates (BoW query)", query, "DB grows to all keyframes");
  row("loop: detect (query + groups + consistency)", candidates);

  // Geometric verification of a true loop (query at 350 deg vs keyframe 0).
  Timing verify;
  for (int r = 0; r < repeats; ++r) {
    timed(verify, [&] { detector.verify(*kfs[35], {kfs[0]}); });
  }
  row("loop: verify (3D-3D RANSAC, search, pose)", verify);

  // Relocalization of frames between keyframes, candidates from the recognizer.
  Relocalizer relocalizer;
  Timing reloc_total, reloc_only;
  int successes = 0;
  for (int r = 0; r < repeats; ++r) {
    const int i = (7 * r) % 36;
    Eigen::Isometry3d T = scene.true_T_world_cam(i) * Eigen::Isometry3d(Eigen::AngleAxisd(0.08, Eigen::Vector3d::UnitY()));
    Frame frame = scene.make_frame(1000 + static_cast<std::uint64_t>(r), T);
    std::vector<RelocalizationCandidate> cands;
    BowDescription d;
    timed(reloc_total, [&] {
      d = recognizer.describe(frame.descriptors());
      for (const auto& c : recognizer.relocalization_candidates(d.bow)) {
        cands.push_back({scene.map().keyframe(c.id), recognizer.description(c.id)->features});
      }
      RelocalizationResult res;
      timed(reloc_only, [&] { res = relocalizer.relocalize(frame, d.features, cands); });
      successes += res.success ? 1 : 0;
    });
  }
  row("reloc: describe + candidates + relocalize", reloc_total);
  row("reloc: relocalize (given candidates)", reloc_only);
  std::printf("relocalization successes: %d / %d\n", successes, repeats);

  // A full closure in synchronous mode: correction and global BA.
  {
    test::LoopScene loop_scene;
    PlaceRecognizer loop_recognizer(vocabulary);
    LoopCloserOptions options;
    options.threaded = false;
    LoopCloser closer(loop_scene.map(), loop_recognizer, options);
    for (int i = 0; i < 42 && closer.loops().empty(); ++i) {
      closer.submit(loop_scene.add_keyframe(i));
      closer.process_pending();
    }
    const LoopCloserStats s = closer.stats();
    std::printf("loop closure: %d loop(s) over %d keyframes; detection total %.1f ms (%.2f ms/keyframe), "
                "correction %.1f ms, global BA %.1f ms\n",
                s.loops_closed, s.keyframes, s.detection_ms, s.detection_ms / std::max(1, s.keyframes),
                s.correction_ms, s.global_bundle_adjustment_ms);
  }

  // The committed vocabulary on real images (EuRoC micro clip, 1000 ORB
  // features per image): describe every left image, index it, query with the
  // right image.
#ifdef STILLSLAM_BENCH_SHARED_DIR
  const std::filesystem::path shared = STILLSLAM_BENCH_SHARED_DIR;
#else
  const std::filesystem::path shared = std::filesystem::path(STILLSLAM_SOURCE_DIR).parent_path() / "shared";
#endif
  const auto voc_path = test::vocabulary_path(std::filesystem::path(STILLSLAM_SOURCE_DIR));
  const auto mav0 = test::euroc_micro_mav0(shared);
  if (!std::filesystem::exists(voc_path) || !std::filesystem::exists(mav0)) {
    std::printf("real data: skipped (need %s and %s)\n", voc_path.c_str(), mav0.c_str());
    return 0;
  }
  Timing load;
  std::shared_ptr<const Vocabulary> real;
  timed(load, [&] { real = std::make_shared<const Vocabulary>(Vocabulary::load(voc_path)); });
  std::printf("real vocabulary: %zu words, k=%d, depth %d, load %.1f ms\n", real->size(), real->k(), real->depth(),
              load.wall[0]);
  const test::EurocStereo euroc = test::load_euroc_stereo(mav0);
  const test::OrbKeyframeFactory factory(euroc.fx, euroc.left[0].cols / 2.0, euroc.left[0].rows / 2.0,
                                         euroc.left[0].cols, euroc.left[0].rows);
  PlaceRecognizer real_recognizer(real);
  Map real_map;
  Timing real_add, real_query;
  for (std::size_t i = 0; i < euroc.left.size(); ++i) {
    const KeyFramePtr kf = factory.keyframe(real_map, i, euroc.left[i]);
    timed(real_add, [&] { real_recognizer.add(*kf); });
  }
  int top1 = 0;
  for (std::size_t i = 0; i < euroc.right.size(); ++i) {
    const Frame query = factory.frame(1000 + i, euroc.right[i]);
    std::vector<PlaceCandidate> c;
    timed(real_query, [&] { c = real_recognizer.relocalization_candidates(real_recognizer.describe(query.descriptors()).bow); });
    // Consecutive 20 Hz frames are near duplicates: count a hit within 0.15 s.
    if (!c.empty()) {
      const auto best = static_cast<long>(c.front().id), own = static_cast<long>(real_map.keyframes()[i]->id());
      if (std::abs(best - own) <= 3) ++top1;
    }
  }
  row("real: describe + index keyframe (1000 ORB)", real_add);
  row("real: describe + relocalization query", real_query, "DB of all left images");
  std::printf("real: right image's best candidate within 3 frames of its own left keyframe: %d / %zu\n", top1, euroc.right.size());
  return 0;
}
