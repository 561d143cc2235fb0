// Map save/load benchmark and the "save -> load -> localization-only run over
// the same sequence: poses within 1 cm of the mapping run" bar.
//
// 1. mapping run over the dataset (deterministic local mapping by default),
//    saving the map at the end (RunOptions::save_map);
// 2. load time of the file alone (load_map_file), file size;
// 3. localization-only run (SystemOptions::load_map + localization_only) over
//    the same frames, optionally starting --start N frames in (so the first
//    frame is not the map origin): no keyframes or points are created, the
//    system relocalizes first and then tracks the loaded map;
// 4. per frame localized in both runs: position and rotation difference of
//    the localization pose to the mapping run's final pose.
//
//   build/bench/bench_map_file --config S.yaml --input DIR [--groundtruth GT]
//       [--vocabulary FILE] [--map FILE] [--start N] [--max-frames N]
//       [--threaded] [--segmentation] [--opencv-threads N]
#include <CLI/CLI.hpp>
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

#include "stillslam/core/error.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/eval/evaluate.h"
#include "stillslam/map/map_file.h"
#include "stillslam/place/vocabulary.h"
#include "stillslam/system/dataset_runner.h"

namespace fs = std::filesystem;
using namespace stillslam;

namespace {

struct Args {
  std::string config, input, groundtruth, vocabulary, map = "/tmp/bench_map_file.map";
  bool threaded = false, segmentation = false;
  std::size_t start = 0, max_frames = 0;
  int opencv_threads = 1;
};

Args parse(int argc, char** argv) {
  Args a;
  CLI::App app("Map save/load benchmark (see the comment at the top of bench/bench_map_file.cpp)", "bench_map_file");
  app.add_option("--config", a.config, "settings YAML")->required();
  app.add_option("--input", a.input, "dataset folder")->required();
  app.add_option("--groundtruth", a.groundtruth, "ground-truth trajectory (TUM) for ATE");
  app.add_option("--vocabulary", a.vocabulary, "ORB vocabulary file");
  app.add_option("--map", a.map, "map file to write and read")->capture_default_str();
  app.add_option("--start", a.start, "first frame of the resumed run")->capture_default_str();
  app.add_option("--max-frames", a.max_frames, "stop after N frames (0: all)")->capture_default_str();
  app.add_flag("--threaded", a.threaded, "local mapping in its own thread");
  app.add_flag("--segmentation", a.segmentation, "run with the segmentation front end");
  app.add_option("--opencv-threads", a.opencv_threads, "cv::setNumThreads (-1: OpenCV's default)")
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::exit(app.exit(e));  // --help prints and exits 0; bad values print CLI11's message and exit non-zero
  }
  return a;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(std::lround(q * static_cast<double>(v.size() - 1)))];
}

void print_ate(const char* name, const Args& args, const Trajectory& est) {
  if (args.groundtruth.empty() || est.empty()) return;
  const EvaluationResult ev = evaluate(read_trajectory(args.groundtruth), est, EvaluationOptions{});
  std::printf("  ATE %-22s rmse %.4f m over %zu poses\n", name, ev.ape_stats.rmse, ev.pairs);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args args = parse(argc, argv);
    if (args.opencv_threads >= 0) cv::setNumThreads(args.opencv_threads);
    const Settings settings = load_settings(args.config);
    const auto dataset = open_dataset(args.input, settings);
    const fs::path vocabulary = resolve_vocabulary_option(args.vocabulary);
    if (vocabulary.empty()) throw Error("bench_map_file needs a vocabulary (relocalization): pass --vocabulary FILE");

    RunOptions mapping;
    mapping.system.use_segmentation = args.segmentation;
    mapping.system.deterministic = !args.threaded;
    mapping.system.vocabulary_path = vocabulary;
    if (args.max_frames > 0) mapping.max_frames = args.max_frames;
    mapping.save_map = args.map;
    std::printf("mapping run: %s (%zu frames, %s)\n", args.input.c_str(),
                std::min(dataset->size(), args.max_frames ? args.max_frames : dataset->size()),
                to_string(dataset->sensor()));
    const RunResult mapped = run_dataset(settings, *dataset, mapping);
    if (mapped.error) throw Error("mapping run failed: " + *mapped.error);
    if (!mapped.map_file) throw Error("mapping run saved no map: " + mapped.map_file_error.value_or("?"));
    std::printf("  tracked %zu of %zu frames, %zu keyframes, %zu points, %zu maps\n", mapped.trajectory.size(),
                mapped.frames.size(), mapped.map_file->keyframes, mapped.map_file->map_points, mapped.map_file->maps);
    std::printf("  save: %.1f ms, file %s: %.2f MB (%.2f MB before zstd; %.1f kB per keyframe)\n", mapped.save_map_ms,
                args.map.c_str(), static_cast<double>(mapped.map_file->bytes) / 1e6,
                static_cast<double>(mapped.map_file->raw_bytes) / 1e6,
                static_cast<double>(mapped.map_file->bytes) / 1e3 /
                    static_cast<double>(std::max<std::size_t>(1, mapped.map_file->keyframes)));

    // Load time of the file alone (the localization run loads it again).
    {
      const auto vocab = Vocabulary::load(vocabulary);
      MapFileContext context;
      context.sensor = to_string(dataset->sensor());
      context.setup = make_camera_setup(settings, dataset->sensor(), dataset->rectified_stereo());
      context.vocabulary_checksum = vocabulary_fingerprint(vocab);
      Stopwatch load;
      const MapFileContents contents = load_map_file(args.map, context);
      std::printf("  load: %.1f ms (%zu maps, covisibility rebuilt)\n", load.elapsed_ms(), contents.maps.size());
    }

    RunOptions localization = mapping;
    localization.save_map.clear();
    localization.system.load_map = args.map;
    localization.system.localization_only = true;
    localization.first_frame = args.start;
    std::printf("localization-only run from frame %zu\n", args.start);
    const RunResult localized = run_dataset(settings, *dataset, localization);
    if (localized.error) throw Error("localization run failed: " + *localized.error);

    std::map<double, Eigen::Isometry3d> reference;
    for (const StampedPose& p : mapped.trajectory) reference.emplace(p.timestamp, p.T_world_cam);
    std::vector<double> position_cm, rotation_deg;
    for (const StampedPose& p : localized.trajectory) {
      const auto it = reference.find(p.timestamp);
      if (it == reference.end()) continue;
      position_cm.push_back(100.0 * (p.T_world_cam.translation() - it->second.translation()).norm());
      const Eigen::AngleAxisd d(Eigen::Matrix3d(p.T_world_cam.linear().transpose() * it->second.linear()));
      rotation_deg.push_back(std::abs(d.angle()) * 180.0 / M_PI);
    }
    std::size_t first_localized = localized.frames.size();
    for (std::size_t i = 0; i < localized.frames.size(); ++i) {
      if (localized.frames[i].has_pose) {
        first_localized = i;
        break;
      }
    }
    std::printf("  localized %zu of %zu frames (first at frame %zu of the run), keyframes after the run %zu "
                "(created: %d)\n",
                localized.trajectory.size(), localized.frames.size(), first_localized, localized.keyframes.size(),
                static_cast<int>(localized.keyframes.size()) - static_cast<int>(mapped.map_file->keyframes));
    std::printf("  pose difference to the mapping run over %zu frames: position max %.3f cm, median %.3f cm, "
                "p95 %.3f cm; rotation max %.3f deg, median %.3f deg\n",
                position_cm.size(), percentile(position_cm, 1.0), percentile(position_cm, 0.5),
                percentile(position_cm, 0.95), percentile(rotation_deg, 1.0), percentile(rotation_deg, 0.5));
    print_ate("mapping run", args, mapped.trajectory);
    print_ate("localization run", args, localized.trajectory);
    const bool bar = !position_cm.empty() && percentile(position_cm, 1.0) <= 1.0;
    std::printf("bar (every localized pose within 1 cm of the mapping run): %s\n", bar ? "met" : "NOT met");
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_map_file: %s\n", e.what());
    return 1;
  }
}
