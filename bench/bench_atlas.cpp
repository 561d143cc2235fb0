// Atlas bar (issue #6): "with relocalization impossible, a new map starts and
// is merged back later". Runs the System over a rendered sequence (`stillslam
// simulate`) in which frames [A, B) are black and frames [B, C) are left out,
// so that when the images come back the camera has jumped to a place the
// first map has not seen: relocalization cannot succeed, a new map starts, and
// when the camera later returns to places of the first map the maps merge.
// Prints the frame numbers (loss, new map, merge), the per-map accuracy and
// the ATE over the whole sequence (SE3 alignment, every tracked frame, after
// the merge), and the same run without merging for comparison.
//
//   build/bench/bench_atlas --input DIR [--config YAML] --blank A:B --resume C
//       [--vocabulary FILE] [--new-map-after N] [--threaded] [--max-frames N] [--no-comparison]
//
// e.g. stillslam simulate --out /tmp/atlas_loop --trajectory loop --frames 330 --fps 15 --no-people --seed 1
//      build/bench/bench_atlas --input /tmp/atlas_loop --blank 45:60 --resume 150
#include <CLI/CLI.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>

#include "stillslam/core/error.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/eval/evaluate.h"
#include "stillslam/io/dataset.h"
#include "stillslam/system/system.h"

namespace fs = std::filesystem;
using namespace stillslam;

namespace {

struct Args {
  std::string input, config, vocabulary;
  std::size_t blank_begin = 0, blank_end = 0, resume = 0, max_frames = 0;
  int new_map_after = -1;
  bool threaded = false;
  bool compare = true;  // also run without merging
};

Args parse(int argc, char** argv) {
  Args a;
  std::string blank;
  bool no_comparison = false;
  CLI::App app("Atlas benchmark (see the comment at the top of bench/bench_atlas.cpp)", "bench_atlas");
  app.add_option("--input", a.input, "dataset folder")->required();
  app.add_option("--config", a.config, "settings YAML (default: INPUT/settings.yaml)");
  app.add_option("--vocabulary", a.vocabulary, "ORB vocabulary file");
  app.add_option("--blank", blank, "A:B: frames A..B-1 black")->required();
  app.add_option("--resume", a.resume, "frame C where the camera resumes (B <= C)")->required();
  app.add_option("--new-map-after", a.new_map_after, "SystemOptions::new_map_after_lost_frames (-1: default)")
      ->capture_default_str();
  app.add_option("--max-frames", a.max_frames, "stop after N frames (0: all)")->capture_default_str();
  app.add_flag("--threaded", a.threaded, "local mapping in its own thread");
  app.add_flag("--no-comparison", no_comparison, "skip the run without merging");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::exit(app.exit(e));  // --help prints and exits 0; bad values print CLI11's message and exit non-zero
  }
  a.compare = !no_comparison;
  const auto colon = blank.find(':');
  if (colon == std::string::npos) throw Error("--blank A:B (frames A..B-1 black)");
  a.blank_begin = std::stoul(blank.substr(0, colon));
  a.blank_end = std::stoul(blank.substr(colon + 1));
  if (a.blank_end <= a.blank_begin || a.resume < a.blank_end) {
    throw Error("usage: bench_atlas --input DIR --blank A:B --resume C (A < B <= C)");
  }
  if (a.config.empty()) a.config = (fs::path(a.input) / "settings.yaml").string();
  return a;
}

struct Outcome {
  std::vector<std::size_t> source_index;  // dataset frame of each processed frame
  std::vector<FrameStats> frames;
  std::vector<MapPose> trajectory;
  std::vector<MapMergeStats> merges;
  std::size_t maps = 0;
  int new_maps = 0;
  double seconds = 0;
};

Outcome run(const Args& a, const Settings& settings, const Dataset& dataset, bool merging) {
  SystemOptions options;
  options.deterministic = !a.threaded;
  options.vocabulary_path = resolve_vocabulary_option(a.vocabulary);
  options.new_map_after_lost_frames = a.new_map_after;
  Settings merge_settings = settings;
  merge_settings.map_merging = merging;
  System system(merge_settings, dataset.sensor(), dataset.rectified_stereo(), options);
  Outcome out;
  Stopwatch wall;
  std::size_t n = dataset.size();
  if (a.max_frames > 0) n = std::min(n, a.max_frames);
  for (std::size_t i = 0; i < n; ++i) {
    if (i >= a.blank_end && i < a.resume) continue;
    SensorFrame f = dataset.load(i);
    if (!f.valid) continue;
    if (i >= a.blank_begin && i < a.blank_end) {
      f.gray.setTo(0);
      if (!f.color.empty()) f.color.setTo(0);
      if (!f.right.empty()) f.right.setTo(0);
    }
    out.source_index.push_back(i);
    FrameStats stats = system.process(f);
    mark_start_frames_posed(out.frames, stats);  // the frames the map's start waited on
    out.frames.push_back(std::move(stats));
  }
  system.shutdown();
  out.seconds = wall.elapsed_ms() / 1000.0;
  out.trajectory = system.trajectory_with_maps();
  out.merges = system.merges();
  out.maps = system.num_maps();
  out.new_maps = system.new_maps_started();
  return out;
}

double ate(const Trajectory& gt, const std::vector<MapPose>& t, std::optional<std::uint64_t> map_id, std::size_t* n) {
  Trajectory est;
  for (const MapPose& p : t) {
    if (!map_id || p.map_id == *map_id) est.push_back(p.pose);
  }
  *n = est.size();
  if (est.size() < 3) return -1;
  return evaluate(gt, est, EvaluationOptions{}).ape_stats.rmse;
}

void report(const char* title, const Outcome& o, const Trajectory& gt) {
  std::printf("\n== %s (%.1f s)\n", title, o.seconds);
  std::size_t tracked = 0;
  std::optional<std::size_t> first_lost;
  for (std::size_t k = 0; k < o.frames.size(); ++k) {
    const FrameStats& f = o.frames[k];
    const std::size_t i = o.source_index[k];
    tracked += f.has_pose ? 1 : 0;
    if (f.state == TrackingState::Lost && !first_lost) {
      first_lost = i;
      std::printf("  frame %zu: lost (%s)\n", i, f.reason.c_str());
    }
    if (f.state != TrackingState::Lost) first_lost.reset();
    if (f.reason == "relocalized") std::printf("  frame %zu: relocalized in map %llu\n", i, (unsigned long long)f.map_id);
    if (f.new_map) std::printf("  frame %zu: new map starts with the next frame with depth\n", i);
    if (f.reason == "initialized" || f.reason.starts_with("map started")) {
      std::printf("  frame %zu: map %llu initialized (%zu earlier frames posed)\n", i, (unsigned long long)f.map_id,
                  f.start_frames_posed.size());
    }
    if (f.merged) std::printf("  frame %zu: active map merged into an older map\n", i);
  }
  for (const MapMergeStats& m : o.merges) {
    std::printf("  merge: map %llu into map %llu (keyframe %llu recognized as %llu, %d inliers, %d points fused, "
                "%d keyframes moved, welding BA %d free / %d fixed keyframes)\n",
                (unsigned long long)m.source_map, (unsigned long long)m.target_map, (unsigned long long)m.query_id,
                (unsigned long long)m.loop_id, m.inliers, m.fused_points, m.moved_keyframes, m.welding_keyframes,
                m.welding_fixed_keyframes);
  }
  std::printf("  frames processed %zu, tracked %zu, maps at the end %zu, new maps %d, merges %zu\n", o.frames.size(),
              tracked, o.maps, o.new_maps, o.merges.size());
  std::map<std::uint64_t, int> ids;
  for (const MapPose& p : o.trajectory) ++ids[p.map_id];
  for (const auto& [id, count] : ids) {
    std::size_t n = 0;
    const double e = ate(gt, o.trajectory, id, &n);
    std::printf("  map %llu: %zu poses, ATE rmse %.4f m (own frame, SE3-aligned alone)\n", (unsigned long long)id, n, e);
  }
  std::size_t n = 0;
  const double e = ate(gt, o.trajectory, std::nullopt, &n);
  std::printf("  whole trajectory.txt: %zu poses, ATE rmse %.4f m (one SE3 alignment for all)\n", n, e);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args a = parse(argc, argv);
    const Settings settings = load_settings(a.config);
    const auto dataset = open_dataset(a.input, settings);
    const fs::path gt_path = fs::path(a.input) / "groundtruth.txt";
    if (!fs::exists(gt_path)) throw Error(gt_path.string() + " not found (a `stillslam simulate` folder has it)");
    const Trajectory gt = read_trajectory(gt_path);
    std::printf("%s: %zu frames, black %zu..%zu, frames %zu..%zu left out, %s\n", a.input.c_str(), dataset->size(),
                a.blank_begin, a.blank_end - 1, a.blank_end, a.resume - 1,
                a.threaded ? "threaded" : "deterministic");
    report("atlas with merging", run(a, settings, *dataset, true), gt);
    if (a.compare) report("atlas without merging", run(a, settings, *dataset, false), gt);
    return 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_atlas: %s\n", e.what());
    return 1;
  }
}
