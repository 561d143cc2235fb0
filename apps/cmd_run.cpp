// `stillslam run`: SLAM over a dataset folder (TUM RGB-D, EuRoC, KITTI layout) or a ROS 2 bag (--topics).
// Writes DIR/trajectory_live.txt while running (whole lines only, so it reads
// back after a crash or kill), and at the end DIR/trajectory.txt (final
// estimate, every tracked frame), DIR/keyframes.txt and DIR/stats.json, each
// written whole or not at all (apps/run_outputs.h). SIGINT, SIGTERM, SIGHUP
// and SIGQUIT stop the run and write all outputs (apps/signal_watcher.h); the
// exit code says how the run ended (kExitCodes below).
// Atlas: trajectory.txt holds the frames of every map, each in its own map's
// frame until that map is merged; DIR/trajectory_maps.txt is the same in TUM
// with a 9th column, the map id (readers of TUM ignore it).
// --save-map FILE writes every map at the end (also after a signal or an input
// error); --load-map FILE starts from a saved map (relocalizing first), and
// with --localization only tracks against it (no keyframes, no mapping).
// --save-frames DIR writes the annotated frames as PNG (apps/frame_saver.h).
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "commands.h"
#include "frame_saver.h"
#include "opencv_threads.h"
#include "run_outputs.h"
#include "viewer/run_viewer.h"
#include "signal_watcher.h"
#include "stillslam/core/error.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/eval/evaluate.h"
#include "stillslam/io/bag_camera_info.h"
#include "stillslam/io/bag_reader.h"
#include "stillslam/io/dataset.h"
#include "stillslam/settings/settings.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/system/run_result_json.h"
#include "stillslam/system/dataset_runner.h"
#include "stillslam/system/run_summary.h"

namespace stillslam::apps {
namespace {

namespace fs = std::filesystem;

constexpr const char* kExitCodes =
    "Exit codes: 0 the run finished (all frames, or --max-frames); 1 an error (bad input or usage, an output "
    "that could not be written; the outputs that could be written are kept); 2 an internal error (a bug); "
    "128+N stopped by signal N with all outputs written: 130 SIGINT (Ctrl-C), 143 SIGTERM, 129 SIGHUP "
    "(terminal or ssh session closed), 131 SIGQUIT. "
    "stats.json's \"end\" says the same: reason finished | max_frames | interrupted | input_error, the signal, "
    "frames_processed, frames_in_input.";

struct RunArgs {
  std::string config, input, output, groundtruth, vocabulary;
  bool no_segmentation = false, realtime = false, deterministic = false, no_loop_closing = false;
  bool raw_trajectory = false;
  bool preload = false;
  std::size_t preload_limit_mb = kDefaultPreloadLimitMb;
  bool skip_bad_frames = false;
  std::string save_frames;  // --save-frames DIR
  int save_frames_every = 1;
  std::string save_frames_format = "png";
  std::string save_map, load_map;
  bool localization = false;
  bool force = false;
  std::size_t max_frames = 0;
  int new_map_after_lost = -1;
  std::vector<std::string> topics;  // ROS 2 bag input
  double pair_tolerance = 0.02;
  bool side_by_side = false, camera_info_from_bag = false;
  RunViewerArgs viewer;
};

std::optional<fs::path> find_groundtruth(const RunArgs& args) {
  if (!args.groundtruth.empty()) return fs::path(args.groundtruth);
  const fs::path candidate = fs::path(args.input) / "groundtruth.txt";
  if (fs::exists(candidate)) return candidate;
  return std::nullopt;
}

void run(const RunArgs& args) {
  SignalWatcher signals;  // before anything else: a signal from now on stops the run cleanly
  const fs::path out_dir(args.output);
  const std::vector<fs::path> previous = previous_run_files(out_dir);
  if (!previous.empty() && !args.force) {
    std::string names;
    for (const fs::path& f : previous) names += (names.empty() ? "" : ", ") + f.filename().string();
    throw Error("output folder " + out_dir.string() + " holds the outputs of an earlier run (" + names +
                "); choose another folder or pass --force to replace them");
  }
  if (!args.save_map.empty()) check_map_path(args.save_map, out_dir);
  Settings settings = load_settings(args.config);
  set_opencv_threads(settings.segmentation.threads);
  DatasetOptions dataset_options;
  dataset_options.skip_bad_frames = args.skip_bad_frames;
  dataset_options.topics = args.topics;
  dataset_options.side_by_side = args.side_by_side;
  dataset_options.max_dt = args.pair_tolerance;
  if ((!args.topics.empty() || args.side_by_side || args.camera_info_from_bag) && !is_bag_path(args.input)) {
    throw Error("--topics, --side-by-side and --camera-info-from-bag apply to ROS 2 bags, and " + args.input +
                " is not one (a folder with metadata.yaml, or a .db3 / .mcap file)");
  }
  if (args.camera_info_from_bag) {
    if (args.side_by_side) {
      throw Error("--camera-info-from-bag does not apply to --side-by-side (a side-by-side topic has no CameraInfo "
                  "for each half): give stereo settings describing one half");
    }
    apply_bag_camera_info(settings, *open_bag(args.input), args.topics);
  }
  const auto dataset = open_dataset(args.input, settings, dataset_options);
  std::unique_ptr<FrameSaver> saver;
  if (!args.save_frames.empty()) {
    FrameSaverOptions saver_options;
    saver_options.dir = args.save_frames;
    saver_options.every = args.save_frames_every;
    saver_options.format = args.save_frames_format;
    saver_options.wait_when_full = args.deterministic;  // a deterministic run saves every frame
    saver_options.replace = args.force;
    saver = std::make_unique<FrameSaver>(saver_options);
  }
  prepare_output_folder(out_dir, previous);

  RunOptions options;
  options.system.use_segmentation = !args.no_segmentation;
  options.system.deterministic = args.deterministic;
  options.system.vocabulary_path = resolve_vocabulary_option(args.vocabulary);
  options.system.loop_closing = !args.no_loop_closing;
  options.system.trajectory_refinement.enabled = !args.raw_trajectory;
  options.system.new_map_after_lost_frames = args.new_map_after_lost;
  options.system.load_map = args.load_map;
  options.system.localization_only = args.localization;
  options.save_map = args.save_map;
  options.realtime = args.realtime;
  if (args.preload) options.preload_max_bytes = args.preload_limit_mb << 20;
  if (args.max_frames > 0) options.max_frames = args.max_frames;
  options.stop = &signals.stop();
  const std::unique_ptr<RunViewer> viewer = start_run_viewer(args.viewer, settings, options, find_groundtruth(args));

  TrajectoryWriter live(out_dir / "trajectory_live.txt");
  std::vector<std::size_t> features_removed;  // per processed frame, from its snapshot
  const std::size_t total = options.max_frames ? std::min(*options.max_frames, dataset->size()) : dataset->size();
  options.on_frame = [&](const FrameStats& f, const System& system) {
    for (const FrameStats::EarlierPose& p : f.start_frames_posed) live.write({p.timestamp, p.T_world_cam});
    if (f.has_pose) live.write({f.timestamp, *system.last_T_world_cam()});
    std::shared_ptr<const FrameSnapshot> snapshot = system.publisher().frame().value;
    features_removed.push_back(snapshot ? snapshot->removed_keypoints.size() : 0);
    if (saver) saver->offer(std::move(snapshot));
  };
  // A line rewritten in place on a terminal, a plain line every 10 s in a log.
  options.progress = ProgressOptions{.terminal = isatty(fileno(stderr)) != 0};
  spdlog::info("run: {} frames of {} ({}), segmentation {}, relocalization {}, loop closing {}", total, args.input,
               to_string(dataset->sensor()), options.system.use_segmentation && settings.segmentation.enabled ? "on" : "off",
               options.system.vocabulary_path.empty() ? "off" : "on",
               options.system.vocabulary_path.empty() || !options.system.loop_closing || args.localization ? "off" : "on");
  if (args.localization) spdlog::info("localization only in {}: no keyframes, no mapping", args.load_map);
  const RunResult result = run_dataset(settings, *dataset, options);
  if (saver) saver->finish();

  const RunSummary summary = summarize_run(result.frames);
  nlohmann::json stats = run_result_json(result, features_removed);
  stats["config"] = fs::absolute(args.config).string();  // absolute: `stillslam report` reads it from anywhere
  stats["input"] = fs::absolute(args.input).string();
  stats["segmentation"] = options.system.use_segmentation && settings.segmentation.enabled;
  stats["deterministic"] = args.deterministic;
  stats["vocabulary"] = options.system.vocabulary_path.string();
  stats["loop_closing"] = !options.system.vocabulary_path.empty() && options.system.loop_closing;
  stats["end"]["signal"] = result.interrupted ? nlohmann::json(signal_name(signals.signal())) : nlohmann::json();
  if (!args.load_map.empty()) stats["load_map"] = args.load_map;
  stats["localization_only"] = args.localization;
  if (result.map_file) stats["map_file"]["path"] = args.save_map;

  std::cout << "frames: " << summary.frames << ", tracked: " << summary.tracked << " ("
            << 100.0 * summary.tracked_ratio() << " %), keyframes: " << result.keyframes.size()
            << ", map points: " << result.map_points << ", relocalizations: " << result.relocalizations
            << ", loops closed: " << result.loop_closer.loops_closed << "\n";
  std::cout << "time per frame [ms] mean " << summary.total_ms.mean << ", median " << summary.total_ms.median
            << ", p95 " << summary.total_ms.p95 << " (ORB extraction " << 100.0 * summary.extraction_share
            << " %; tracking only: median " << summary.tracking_ms.median << ")\n";
  if (saver) {
    stats["saved_frames"] = {{"dir", fs::absolute(args.save_frames).string()}, {"every", args.save_frames_every},
                             {"format", args.save_frames_format},
                             {"written", saver->written()}, {"skipped", saver->skipped()},
                             {"failed", saver->failed()}, {"mean_write_ms", saver->mean_write_ms()}};
  }
  const auto gt_path = find_groundtruth(args);
  if (gt_path) stats["groundtruth"] = fs::absolute(*gt_path).string();
  if (gt_path && !result.trajectory.empty()) {
    try {
      const EvaluationResult ev = evaluate(read_trajectory(*gt_path), result.trajectory, EvaluationOptions{});
      stats["summary"]["ate_rmse"] = ev.ape_stats.rmse;
      stats["summary"]["ate_pairs"] = ev.pairs;
      std::cout << "ATE rmse " << ev.ape_stats.rmse << " m over " << ev.pairs << " poses (SE3 alignment, "
                << gt_path->string() << ")\n";
    } catch (const Error& e) {
      spdlog::warn("no ATE: {}", e.what());
    }
  }
  const std::vector<std::string> write_errors = write_run_outputs(out_dir, result, stats);
  if (write_errors.empty()) {
    std::cout << "wrote " << (out_dir / "trajectory.txt").string()
              << ", keyframes.txt, trajectory_maps.txt, stats.json\n";
  }
  if (result.map_file) {
    std::cout << "saved map " << args.save_map << ": " << result.map_file->maps << " maps, "
              << result.map_file->keyframes << " keyframes, " << result.map_file->map_points << " points, "
              << static_cast<double>(result.map_file->bytes) / 1e6 << " MB, " << result.save_map_ms << " ms\n";
  }
  // Every error is shown; the last one is the exit's message (exit code 1).
  std::vector<std::string> errors = write_errors;
  if (result.map_file_error) errors.push_back(*result.map_file_error);
  if (!errors.empty()) errors.back() += " (the outputs that could be written are kept)";
  if (result.error) errors.push_back(*result.error + " (the trajectory so far is in " + out_dir.string() + ")");
  for (std::size_t i = 0; i + 1 < errors.size(); ++i) spdlog::error("{}", errors[i]);
  if (!errors.empty()) throw Error(errors.back());
  if (result.interrupted) {
    spdlog::info("stopped by {} after {} of {} frames; outputs written to {}", signal_name(signals.signal()),
                 result.frames.size(), result.frames_in_input, out_dir.string());
    throw CLI::RuntimeError(128 + signals.signal());
  }
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand("run", "run SLAM on a dataset folder or ROS 2 bag and write the trajectory and stats");
  cmd->add_option("--config", args->config, "settings YAML (ORB-SLAM3 style)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--input", args->input,
                  "dataset folder (TUM RGB-D, EuRoC or KITTI layout) or ROS 2 bag (folder with metadata.yaml, or a "
                  ".db3 / .mcap file)")
      ->required();
  cmd->add_option("--topics", args->topics,
                  "ROS 2 bag input: image topics LEFT,RIGHT (stereo) or RGB,DEPTH (RGB-D), or one side-by-side topic")
      ->delimiter(',');
  cmd->add_option("--pair-tolerance", args->pair_tolerance,
                  "seconds within which two images pair up (bag topics by header stamp, TUM rgb/depth, EuRoC "
                  "cam0/cam1; default 0.02)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--side-by-side", args->side_by_side,
                "ROS 2 bag input: the one --topics topic holds left|right stereo images side by side (ZED); each "
                "image is split into two halves");
  cmd->add_flag("--camera-info-from-bag", args->camera_info_from_bag,
                "ROS 2 bag input: take the camera calibration (K, D, size; stereo baseline and rotation from R and P) "
                "from the sensor_msgs/CameraInfo next to each image topic (/ns/image_raw -> /ns/camera_info) instead "
                "of the settings");
  cmd->add_option("--output", args->output,
                  "output folder; one that holds an earlier run's trajectory*.txt, keyframes.txt or stats.json is "
                  "refused unless --force is given")
      ->required();
  cmd->add_flag("--force", args->force,
                "remove an earlier run's trajectory*.txt, keyframes.txt and stats.json from the output folder first "
                "(and its frame_*.png/jpg from the --save-frames folder; nothing else is touched)");
  cmd->add_flag("--no-segmentation", args->no_segmentation, "same pipeline without dynamic masks (baseline)");
  cmd->add_option("--max-frames", args->max_frames, "process at most N frames");
  cmd->add_flag("--realtime", args->realtime, "pace frames by timestamps, dropping late ones");
  cmd->add_flag("--preload", args->preload,
                "decode every frame into memory before the run starts, so --realtime does not pay decoding the "
                "dataset's image files (a camera delivers pixels); stats.json: summary.preload");
  cmd->add_option("--preload-limit-mb", args->preload_limit_mb,
                  "with --preload: refuse (before decoding them all) when the frames need more memory than this")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--skip-bad-frames", args->skip_bad_frames,
                "go on past a missing or unreadable frame (a warning names each; stats.json counts them in "
                "summary.skipped_frames) instead of ending the run there");
  cmd->add_flag("--deterministic", args->deterministic,
                "synchronous local mapping: same input, same trajectory bit for bit");
  cmd->add_option("--vocabulary", args->vocabulary,
                  "ORB vocabulary for relocalization and loop closing (default: vocab/orb_vocabulary.bin of the "
                  "repository the binary was built in; 'none' disables both)");
  cmd->add_flag("--raw-trajectory", args->raw_trajectory, "the poses as tracked, without re-estimating each frame against the final map");
  cmd->add_flag("--no-loop-closing", args->no_loop_closing,
                "no loop detection/correction (keyframes are still indexed for relocalization)");
  cmd->add_option("--new-map-after-lost", args->new_map_after_lost,
                  "start a new map after N frames lost (default: 1 s of frames with a vocabulary; 0: never)");
  cmd->add_option("--save-map", args->save_map,
                  "save every map to FILE at the end (also when the run stops early, e.g. Ctrl-C); a folder or a "
                  "missing parent folder is refused before the run starts");
  CLI::Option* load = cmd->add_option("--load-map", args->load_map,
                                      "start from a map saved with --save-map (needs the same vocabulary, sensor "
                                      "and calibration); tracking relocalizes in it first")
                          ->check(CLI::ExistingFile);
  cmd->add_flag("--localization", args->localization,
                "localization only: track against the loaded map without changing it (no keyframes, no "
                "mapping, no loop closing)")
      ->needs(load);
  cmd->add_option("--save-frames", args->save_frames,
                  "write every processed frame, annotated (kept features, removed features, mask outlines, "
                  "tracking state), as DIR/frame_<index>_<timestamp>.png; frames the writer cannot keep up with "
                  "are skipped and counted, except with --deterministic");
  cmd->add_option("--save-frames-every", args->save_frames_every, "with --save-frames: every Nth frame only")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--save-frames-format", args->save_frames_format,
                  "with --save-frames: png (lossless) or jpg (quality 90, much faster to write)")
      ->check(CLI::IsMember({"png", "jpg"}))
      ->capture_default_str();
  cmd->add_option("--groundtruth", args->groundtruth,
                  "ground truth for the closing ATE (default: groundtruth.txt in the input folder)");
  add_viewer_options(*cmd, args->viewer);
  cmd->footer(kExitCodes);
  cmd->callback([args] { run(*args); });
}

}  // namespace stillslam::apps
