// End-to-end SLAM benchmark on a dataset folder: accuracy (ATE against a
// ground truth), robustness (tracked frames, lost frames) and speed (per-frame
// wall and thread-CPU times, ORB extraction share), with local mapping
// running concurrently unless --deterministic. --check-determinism runs the
// deterministic mode twice and compares the trajectories bit for bit.
//
//   build/bench/bench_slam --config S.yaml --input DIR [--groundtruth GT]
//       [--no-segmentation] [--deterministic] [--check-determinism] [--raw-trajectory]
//       [--max-frames N] [--opencv-threads N] [--json OUT] [--vocabulary FILE]
//       [--oracle-masks DIR [--mask-miss-rate R] [--mask-miss-burst S] [--mask-miss-seed N]]
//       [--trajectory OUT] [--keyframe-trajectory OUT] [--live-trajectory OUT]
//       [--realtime] [--segmenter-cost-ms MS] [--variants off,sync,async [--runs N]]
//       [--preload [--preload-limit-mb MB]]
//
// --realtime: frames paced by their timestamps, late ones dropped (as live).
// --preload: every frame decoded into memory before each run's clock starts
// (a camera delivers pixels; PNG decoding is not the system's cost).
// --segmenter-cost-ms: with --oracle-masks, each segmentation first burns
// this much CPU time (the measured YOLO CPU per frame), so asynchronous
// timing is realistic without the model.
// --variants: in one invocation, on identical settings, runs each variant
// (off: no segmentation; sync / async: Segmentation.mode) --runs times,
// interleaved, and prints medians: fps, per-frame time, latency, dropped
// frames, CPU per frame, ATE, and the ratios to "off" and to "sync".
//
// --oracle-masks: a `stillslam simulate` folder; its ground-truth masks/ (in
// associations.txt order) replace YOLO, with the settings' dilation and hold.
// Segmentation "on" with perfect masks: what is left of the gap to the static
// path is geometry (less of the view to track), not missed people.
// --mask-miss-rate: that share of the frames gets no mask (a detector that
// lost the people), chosen with --mask-miss-seed; with --mask-miss-burst S in
// whole bursts of S seconds. bench_mask_misses sweeps the rate.
// --oracle-instances: the folder's instances/ instead, one detection per
// instance with its class (the motion stage's input, issue #19); with
// Motion.enabled the run also prints how the still person and the moved
// objects were treated (oracle_motion_tally.h).
#include <CLI/CLI.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <map>
#include <optional>
#include <vector>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "stillslam/core/error.h"
#include "stillslam/core/json_text.h"
#include "stillslam/eval/evaluate.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/io/tum_dataset.h"
#include "stillslam/system/dataset_runner.h"
#include "stillslam/system/realtime_summary.h"
#include "stillslam/system/run_summary.h"
#include "oracle_instance_segmenter.h"
#include "oracle_motion_tally.h"
#include "oracle_segmenter.h"

namespace fs = std::filesystem;
using namespace stillslam;

namespace {

struct Args {
  std::string config, input, groundtruth, json, oracle_masks, vocabulary, trajectory, keyframe_trajectory,
      live_trajectory;
  std::string oracle_instances;
  bool no_segmentation = false, deterministic = false, check_determinism = false, raw_trajectory = false;
  std::size_t max_frames = 0;
  int opencv_threads = -1;
  bool realtime = false;
  bool preload = false;
  std::size_t preload_limit_mb = kDefaultPreloadLimitMb;
  double segmenter_cost_ms = 0;
  std::vector<std::string> variants;
  int runs = 1;
  oracle::MaskMissOptions misses;
};

Args parse(int argc, char** argv) {
  Args a;
  CLI::App app("End-to-end SLAM benchmark (see the comment at the top of bench/bench_slam.cpp)", "bench_slam");
  app.add_option("--config", a.config, "settings YAML")->required();
  app.add_option("--input", a.input, "dataset folder")->required();
  app.add_option("--groundtruth", a.groundtruth, "ground-truth trajectory (TUM) for ATE");
  app.add_option("--json", a.json, "write the results as JSON here");
  app.add_option("--vocabulary", a.vocabulary, "ORB vocabulary (relocalization, loop closing; default: none)");
  app.add_option("--trajectory", a.trajectory, "write the estimated trajectory here (TUM format)");
  app.add_option("--keyframe-trajectory", a.keyframe_trajectory, "write the keyframes' poses here (TUM format)");
  app.add_option("--live-trajectory", a.live_trajectory,
                 "write each frame's pose as published when it was tracked here (TUM format; online, never moved "
                 "by later mapping)");
  app.add_option("--oracle-masks", a.oracle_masks, "simulate folder whose ground-truth masks/ replace YOLO");
  app.add_option("--oracle-instances", a.oracle_instances,
                 "simulate folder whose ground-truth instances/ (one detection each, with its class) replace YOLO");
  app.add_option("--mask-miss-rate", a.misses.rate, "with --oracle-masks: share of frames without a mask")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--mask-miss-burst", a.misses.burst_seconds, "missed masks in bursts of this many seconds (0: frames)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--mask-miss-seed", a.misses.seed, "seed of the missed frames")->capture_default_str();
  app.add_flag("--no-segmentation", a.no_segmentation, "run without the segmentation front end");
  app.add_flag("--realtime", a.realtime, "pace frames by their timestamps, drop late ones");
  app.add_flag("--preload", a.preload, "decode every frame into memory before the run's clock starts");
  app.add_option("--preload-limit-mb", a.preload_limit_mb, "with --preload: refuse when the frames need more")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--segmenter-cost-ms", a.segmenter_cost_ms, "with --oracle-masks: CPU ms each segmentation burns")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--variants", a.variants, "compare these in one run: off, sync, async (comma separated)")
      ->delimiter(',')
      ->check(CLI::IsMember({"off", "sync", "async"}));
  app.add_option("--runs", a.runs, "with --variants: runs per variant (medians)")->check(CLI::PositiveNumber);
  app.add_flag("--deterministic", a.deterministic, "synchronous local mapping");
  app.add_flag("--raw-trajectory", a.raw_trajectory, "the tracked poses, not re-estimated against the final map");
  app.add_flag("--check-determinism", a.check_determinism, "run the deterministic mode twice and compare");
  app.add_option("--max-frames", a.max_frames, "stop after N frames (0: all)")->capture_default_str();
  app.add_option("--opencv-threads", a.opencv_threads,
                 "cv::setNumThreads (-1: the settings' Segmentation.threads, as stillslam run)")
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::exit(app.exit(e));  // --help prints and exits 0; bad values print CLI11's message and exit non-zero
  }
  return a;
}

void print_timing(const char* name, const TimingSummary& t) {
  std::printf("  %-28s mean %7.2f  median %7.2f  p95 %7.2f  max %7.2f ms\n", name, t.mean, t.median, t.p95, t.max);
}

RunResult run_once(const Settings& settings, const Dataset& dataset, const Args& a, bool deterministic,
                   Trajectory* live = nullptr) {
  RunOptions options;
  if (live) {
    options.on_frame = [live](const FrameStats& f, const System& system) {
      for (const FrameStats::EarlierPose& p : f.start_frames_posed) live->push_back({p.timestamp, p.T_world_cam});
      if (f.has_pose) live->push_back({f.timestamp, *system.last_T_world_cam()});
    };
  }
  options.system.use_segmentation = !a.no_segmentation;
  options.system.vocabulary_path = a.vocabulary;
  if (!a.oracle_masks.empty()) {
    oracle::MaskMissOptions misses = a.misses;
    misses.fps = settings.fps > 0 ? settings.fps : 30.0;
    std::vector<bool> missed = oracle::choose_missed_frames(oracle::oracle_mask_files(a.oracle_masks).size(), misses);
    options.system.segmenter_factory = [dir = a.oracle_masks, missed, cost = a.segmenter_cost_ms] {
      return std::make_unique<oracle::OracleSegmenter>(dir, missed, cost);
    };
  } else if (!a.oracle_instances.empty()) {
    options.system.segmenter_factory = [dir = a.oracle_instances] {
      return std::make_unique<oracle::OracleInstanceSegmenter>(dir);
    };
  } else if (a.misses.rate > 0) {
    throw Error("--mask-miss-rate needs --oracle-masks DIR (the exact masks to miss)");
  } else if (a.segmenter_cost_ms > 0) {
    throw Error("--segmenter-cost-ms needs --oracle-masks DIR (YOLO costs what it costs)");
  }
  options.realtime = a.realtime;
  if (a.preload) options.preload_max_bytes = a.preload_limit_mb << 20;
  options.system.deterministic = deterministic;
  options.system.trajectory_refinement.enabled = !a.raw_trajectory;
  if (a.max_frames > 0) options.max_frames = a.max_frames;
  return run_dataset(settings, dataset, options);
}

std::optional<double> ate_rmse(const Args& a, const Trajectory& estimate) {
  fs::path gt = a.groundtruth;
  if (gt.empty() && fs::exists(fs::path(a.input) / "groundtruth.txt")) gt = fs::path(a.input) / "groundtruth.txt";
  if (gt.empty() || estimate.empty()) return std::nullopt;
  try {
    return evaluate(read_trajectory(gt), estimate, EvaluationOptions{}).ape_stats.rmse;
  } catch (const Error& e) {  // e.g. a realtime run that tracked too few frames to align
    std::printf("  no ATE: %s\n", e.what());
    return std::nullopt;
  }
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// One variant's figures of one run.
std::map<std::string, double> variant_figures(const Args& a, const RunResult& r) {
  const RunSummary s = summarize_run(r.frames);
  const RealtimeSummary rt = summarize_realtime(r);
  std::map<std::string, double> f{{"fps", rt.fps},
                                  {"frame_ms_median", s.total_ms.median},
                                  {"frame_cpu_ms_median", s.total_cpu_ms.median},
                                  {"extraction_cpu_ms_median", s.extraction_cpu_ms.median},
                                  {"propagation_cpu_ms_median", s.propagation_cpu_ms.median},
                                  {"propagation_cpu_ms_mean", s.propagation_cpu_ms.mean},
                                  {"tracker_cpu_ms_median", s.tracking_cpu_ms.median},
                                  {"core_wait_ms_median", s.core_wait_ms.median},
                                  {"core_wait_ms_mean", s.core_wait_ms.mean},
                                  {"latency_ms_median", rt.latency_ms.median},
                                  {"latency_ms_p95", rt.latency_ms.p95},
                                  {"dropped_share", rt.dropped_share},
                                  {"cpu_ms_per_frame", rt.cpu_ms_per_frame},
                                  {"mapping_cpu_ms_per_frame", rt.mapping_cpu_ms_per_frame},
                                  {"tracked_share", s.tracked_ratio()},
                                  {"mean_mask_age", rt.mean_mask_age},
                                  {"frames_waited", static_cast<double>(rt.waited_frames)},
                                  {"segmentation_skips", static_cast<double>(rt.segmentation_skips)},
                                  {"keyframes", static_cast<double>(r.keyframes.size())},
                                  {"keyframes_deferred", static_cast<double>(rt.keyframes_deferred)},
                                  {"keyframes_held", static_cast<double>(rt.keyframes_held)}};
  double held_points_removed = 0;
  for (const FrameStats& frame : r.frames) held_points_removed += frame.held_points_removed;
  f["held_points_removed"] = held_points_removed;
  if (const auto ate = ate_rmse(a, r.trajectory)) f["ate_rmse"] = *ate;
  return f;
}

// --variants: every variant --runs times, interleaved (load hits all alike), medians.
int bench_variants(const Args& a, const Settings& settings, const Dataset& dataset) {
  std::map<std::string, std::map<std::string, std::vector<double>>> figures;  // variant -> figure -> runs
  for (int run = 0; run < a.runs; ++run) {
    for (const std::string& variant : a.variants) {
      Args va = a;
      va.no_segmentation = variant == "off";
      Settings vs = settings;
      if (variant != "off") {
        vs.segmentation.enabled = true;
        vs.segmentation.mode = variant == "async" ? SegmentationMode::Async : SegmentationMode::Sync;
      }
      const RunResult r = run_once(vs, dataset, va, a.deterministic);
      if (r.error) std::printf("run ended early: %s\n", r.error->c_str());
      for (const auto& [name, value] : variant_figures(a, r)) figures[variant][name].push_back(value);
      std::printf("  run %d %-5s fps %6.1f  frame median %6.1f ms  dropped %5.1f %%  cpu/frame %6.1f ms  ATE %s\n",
                  run + 1, variant.c_str(), figures[variant]["fps"].back(), figures[variant]["frame_ms_median"].back(),
                  100 * figures[variant]["dropped_share"].back(), figures[variant]["cpu_ms_per_frame"].back(),
                  figures[variant].count("ate_rmse") ? std::to_string(figures[variant]["ate_rmse"].back()).c_str()
                                                     : "-");
      std::fflush(stdout);
    }
  }
  nlohmann::json out;
  out["input"] = a.input;
  out["realtime"] = a.realtime;
  out["deterministic"] = a.deterministic;
  out["runs"] = a.runs;
  out["segmenter_cost_ms"] = a.segmenter_cost_ms;
  std::printf("%s (%s, %s, %s, medians of %d runs)\n", a.input.c_str(), to_string(dataset.sensor()),
              a.realtime ? "--realtime" : "offline throughput", a.deterministic ? "deterministic" : "concurrent",
              a.runs);
  std::printf("  %-6s %7s %9s %9s %9s %9s %8s %9s %9s %8s %9s %7s\n", "", "fps", "frame ms", "frameCPU", "lat p50",
              "lat p95", "drop %", "CPU/fr", "map CPU", "age", "waited", "ATE");
  for (const std::string& variant : a.variants) {
    if (out["variants"].contains(variant)) continue;
    nlohmann::json v;
    for (auto& [name, values] : figures[variant]) {
      v["median"][name] = median(values);
      v["runs"][name] = values;
    }
    auto m = [&](const char* name) { return figures[variant].count(name) ? median(figures[variant][name]) : -1.0; };
    std::printf("  %-6s %7.1f %9.1f %9.1f %9.1f %9.1f %8.1f %9.1f %9.1f %8.2f %9.0f %7.4f\n", variant.c_str(),
                m("fps"), m("frame_ms_median"), m("frame_cpu_ms_median"), m("latency_ms_median"), m("latency_ms_p95"),
                100 * m("dropped_share"), m("cpu_ms_per_frame"), m("mapping_cpu_ms_per_frame"), m("mean_mask_age"),
                m("frames_waited"), m("ate_rmse"));
    out["variants"][variant] = v;
  }
  // Where the tracking thread's CPU goes (medians over frames, then over runs).
  std::printf("  tracking thread CPU ms/frame (median): %-6s %7s %9s %9s %9s %9s\n", "", "frame", "extract", "propag",
              "tracker", "coreWait");
  for (const std::string& variant : a.variants) {
    auto m = [&](const char* name) { return figures[variant].count(name) ? median(figures[variant][name]) : -1.0; };
    std::printf("  %38s %-6s %7.1f %9.1f %9.2f %9.1f %9.2f  (propagation mean %.2f, core wait mean %.2f)\n", "",
                variant.c_str(), m("frame_cpu_ms_median"), m("extraction_cpu_ms_median"),
                m("propagation_cpu_ms_median"), m("tracker_cpu_ms_median"), m("core_wait_ms_median"),
                m("propagation_cpu_ms_mean"), m("core_wait_ms_mean"));
  }
  auto ratio = [&](const std::string& x, const std::string& y, const char* name) -> std::optional<double> {
    if (!figures.count(x) || !figures.count(y) || !figures[x].count(name) || !figures[y].count(name)) return {};
    const double d = median(figures[y][name]);
    if (d <= 0) return {};
    return median(figures[x][name]) / d;
  };
  for (const char* on : {"sync", "async"}) {
    if (const auto r = ratio(on, "off", "frame_ms_median")) {
      std::printf("  frame time %s / off: %.2f (wall median)", on, *r);
      out["ratios"][std::string(on) + "_over_off_frame_ms"] = *r;
      if (const auto c = ratio(on, "off", "cpu_ms_per_frame")) {
        std::printf(", process CPU/frame %.2f", *c);
        out["ratios"][std::string(on) + "_over_off_cpu_per_frame"] = *c;
      }
      std::printf("\n");
    }
  }
  if (const auto r = ratio("async", "sync", "ate_rmse")) {
    std::printf("  ATE async / sync: %.3f\n", *r);
    out["ratios"]["async_over_sync_ate"] = *r;
  }
  if (!a.json.empty()) std::ofstream(a.json) << json_text(out, 1) << "\n";
  return 0;
}

int bench(const Args& a) {
  const Settings settings = load_settings(a.config);
  // The pool size stillslam run uses (apps/opencv_threads.h), unless given.
  if (a.opencv_threads >= 0) {
    cv::setNumThreads(a.opencv_threads);
  } else if (settings.segmentation.threads > 0) {
    cv::setNumThreads(settings.segmentation.threads);
  }
  const auto dataset = open_dataset(a.input, settings);
  if (!a.variants.empty()) return bench_variants(a, settings, *dataset);
  Trajectory live;
  const RunResult r = run_once(settings, *dataset, a, a.deterministic, a.live_trajectory.empty() ? nullptr : &live);
  if (r.error) std::printf("run ended early: %s\n", r.error->c_str());
  const RunSummary s = summarize_run(r.frames);
  nlohmann::json out;
  out["input"] = a.input;
  out["mask_misses"] = {{"rate", a.misses.rate}, {"burst_seconds", a.misses.burst_seconds}, {"seed", a.misses.seed}};
  out["summary"] = to_json(s);
  out["local_mapping"] = to_json(r.mapper, r.frames.size());
  out["frames"] = nlohmann::json::array();
  for (const FrameStats& f : r.frames) out["frames"].push_back(to_json(f));
  std::printf("%s (%s, segmentation %s, %s)\n", a.input.c_str(), to_string(dataset->sensor()),
              a.no_segmentation ? "off" : "on", a.deterministic ? "deterministic" : "concurrent local mapping");
  std::printf("  frames %zu, tracked %zu (%.1f %%), lost %zu, keyframes %zu (inserted %zu, culled %d), map points %zu\n",
              s.frames, s.tracked, 100.0 * s.tracked_ratio(), s.lost, r.keyframes.size(), s.keyframes_inserted,
              r.mapper.keyframes_culled, r.map_points);
  std::printf("  features per frame: %.0f extracted, %.0f after the dynamic filter, %.0f inliers\n",
              s.mean_keypoints_before, s.mean_keypoints_after, s.mean_inliers);
  std::printf(" wall clock (includes waiting for the CPU on a shared machine):\n");
  print_timing("frame total", s.total_ms);
  print_timing("tracking (after extraction)", s.tracking_ms);
  print_timing("ORB extraction", s.extraction_ms);
  print_timing("segmentation wait", s.segmentation_wait_ms);
  std::printf(" thread CPU time of the tracking thread:\n");
  print_timing("frame total", s.total_cpu_ms);
  print_timing("tracking (after extraction)", s.tracking_cpu_ms);
  print_timing("ORB extraction (left)", s.extraction_cpu_ms);
  const double cpu_share = s.total_cpu_ms.mean > 0 ? s.extraction_cpu_ms.mean / s.total_cpu_ms.mean : 0;
  std::printf("  ORB extraction share: %.1f %% of wall, %.1f %% of CPU\n", 100 * s.extraction_share, 100 * cpu_share);
  std::printf("  local mapping: %d keyframes, %d BA (%d aborted), BA %.1f ms/keyframe, total %.1f ms/keyframe\n",
              r.mapper.keyframes, r.mapper.bundle_adjustments, r.mapper.bundle_adjustments_aborted,
              r.mapper.keyframes ? r.mapper.bundle_adjustment_ms / r.mapper.keyframes : 0.0,
              r.mapper.keyframes ? r.mapper.total_ms / r.mapper.keyframes : 0.0);
  const RealtimeSummary rt = summarize_realtime(r);
  std::printf("  %.1f fps sustained, latency median %.1f / p95 %.1f ms, dropped %zu (%.1f %%), CPU %.1f ms/frame "
              "(mapping %.1f); masks: %zu fresh, %zu carried (mean age %.2f), %zu waited, %zu skipped\n",
              rt.fps, rt.latency_ms.median, rt.latency_ms.p95, rt.dropped_frames, 100 * rt.dropped_share,
              rt.cpu_ms_per_frame, rt.mapping_cpu_ms_per_frame, rt.fresh_masks, rt.carried_masks, rt.mean_mask_age,
              rt.waited_frames, rt.segmentation_skips);
  out["realtime"] = to_json(rt);
  std::printf("  wall %.1f s\n", r.wall_seconds);
  out["extraction_cpu_share"] = cpu_share;
  if (!a.oracle_instances.empty() && settings.motion.enabled) {
    const oracle::MotionTally t =
        oracle::tally_motion(a.oracle_instances, r.frames, settings.motion.span + settings.motion.person_frames);
    std::printf("  motion: still person kept static in %d / %d frames past its window (%.1f %%); moved objects "
                "masked in %d / %d of their moving frames (%.1f %%); %d frames without a pose\n",
                t.still_kept, t.still_frames, t.still_frames ? 100.0 * t.still_kept / t.still_frames : 0.0,
                t.moved_removed, t.moved_frames, t.moved_frames ? 100.0 * t.moved_removed / t.moved_frames : 0.0,
                t.frames_without_pose);
    out["motion"] = {{"still_frames", t.still_frames}, {"still_kept", t.still_kept},
                     {"moved_frames", t.moved_frames}, {"moved_removed", t.moved_removed}};
  }
  if (settings.motion.sparse_view.enabled) {
    // Frames per crowd-fallback action (tracking/sparse_view.h).
    std::array<int, 5> n{};
    for (const FrameStats& f : r.frames) ++n[static_cast<std::size_t>(std::clamp(f.build.motion.sparse_view, 0, 4))];
    std::printf("  sparse view: %d tracked, %d blended, %d predicted, %d refused as a map start\n", n[1], n[2], n[3],
                n[4]);
    out["sparse_view"] = {{"tracked", n[1]}, {"blended", n[2]}, {"predicted", n[3]}, {"no_start", n[4]}};
  }

  fs::path gt = a.groundtruth;
  if (gt.empty() && fs::exists(fs::path(a.input) / "groundtruth.txt")) gt = fs::path(a.input) / "groundtruth.txt";
  if (!gt.empty() && !r.trajectory.empty()) {
    const EvaluationResult ev = evaluate(read_trajectory(gt), r.trajectory, EvaluationOptions{});
    std::printf("  ATE rmse %.5f m (mean %.5f, max %.5f) over %zu poses; RPE trans rmse %.5f m, rot %.4f deg\n",
                ev.ape_stats.rmse, ev.ape_stats.mean, ev.ape_stats.max, ev.pairs, ev.rpe_trans_stats.rmse,
                ev.rpe_rot_stats.rmse);
    out["ate_rmse"] = ev.ape_stats.rmse;
    out["ate_pairs"] = ev.pairs;
  }
  if (a.check_determinism) {
    const RunResult r1 = run_once(settings, *dataset, a, true);
    const RunResult r2 = run_once(settings, *dataset, a, true);
    bool same = r1.trajectory.size() == r2.trajectory.size();
    for (std::size_t i = 0; same && i < r1.trajectory.size(); ++i) {
      same = r1.trajectory[i].timestamp == r2.trajectory[i].timestamp &&
             r1.trajectory[i].T_world_cam.matrix() == r2.trajectory[i].T_world_cam.matrix();
    }
    std::printf("  determinism: two deterministic runs (%zu poses) are %s\n", r1.trajectory.size(),
                same ? "bit-for-bit identical" : "DIFFERENT");
    out["deterministic_identical"] = same;
  }
  if (!a.trajectory.empty()) write_trajectory(a.trajectory, r.trajectory, TrajectoryFormat::Tum);
  if (!a.keyframe_trajectory.empty()) write_trajectory(a.keyframe_trajectory, r.keyframes, TrajectoryFormat::Tum);
  if (!a.live_trajectory.empty()) write_trajectory(a.live_trajectory, live, TrajectoryFormat::Tum);
  if (!a.json.empty()) std::ofstream(a.json) << json_text(out, 1) << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return bench(parse(argc, argv));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_slam: %s\n", e.what());
    return 1;
  }
}
