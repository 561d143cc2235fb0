// `stillslam ros2`: the live ROS 2 node (live_node.h) on Cyclone DDS. Runs
// until Ctrl-C (SIGINT, SIGTERM, SIGHUP, SIGQUIT), --max-frames, or a bad
// input message, then writes the outputs `run` writes into --output
// (trajectory.txt, keyframes.txt, trajectory_maps.txt, stats.json, and the
// map with --save-map); trajectory_live.txt grows while it runs. A signal is
// the normal end of a live node: exit 0.
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <tuple>

#include "commands.h"
#include "frame_assembler.h"
#include "image_topic_args.h"
#include "live_node.h"
#include "opencv_threads.h"
#include "run_outputs.h"
#include "signal_watcher.h"
#include "stillslam/core/error.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/settings/settings.h"
#include "stillslam/system/run_result_json.h"
#include "stillslam/system/run_summary.h"
#include "viewer/run_viewer.h"

namespace stillslam::apps {
namespace {

namespace fs = std::filesystem;

struct Ros2Args {
  std::string config, output = "ros2_output", vocabulary, qos = "default", save_map;
  ros2::ImageTopicArgs images;
  std::string camera_info;
  int domain = 0;
  bool network = false, force = false, no_segmentation = false, deterministic = false, no_loop_closing = false;
  bool raw_trajectory = false, rectified_input = false;
  double pair_tolerance = 0.01;
  std::size_t max_frames = 0, path_max_poses = 10000;
  std::string map_frame = "map", camera_frame = "camera";
  RunViewerArgs viewer;
};

ros2::NodeTopics input_topics(const Ros2Args& args, SensorType sensor) {
  ros2::NodeTopics topics;
  std::tie(topics.first, topics.second) = ros2::image_topics(args.images, sensor, args.config);
  if (args.camera_info != "none") {
    topics.camera_info = args.camera_info.empty() ? ros2::camera_info_topic(topics.first) : args.camera_info;
  }
  return topics;
}

nlohmann::json node_stats(const Ros2Args& args, const ros2::LiveNodeOptions& options,
                          const ros2::LiveNodeResult& result, const SignalWatcher& signals, bool segmentation) {
  const RunResult& run = result.run;
  nlohmann::json stats = run_result_json(run, {});
  stats["config"] = args.config;
  stats["input"] = "ros2";
  stats["segmentation"] = segmentation;
  stats["deterministic"] = args.deterministic;
  stats["ros2"] = {{"domain", args.domain},
                   {"loopback_only", !args.network},
                   {"topics", {options.topics.first, options.topics.second}},
                   {"received", {result.received_first, result.received_second}},
                   {"unpaired", {result.unpaired_first, result.unpaired_second}},
                   {"pairs", run.frames_in_input},
                   {"dropped_stale", result.dropped},
                   {"published_poses", result.published_poses},
                   {"camera_info_messages", result.camera_info_messages}};
  stats["end"]["signal"] = run.interrupted ? nlohmann::json(signal_name(signals.signal())) : nlohmann::json();
  if (run.map_file) stats["map_file"]["path"] = args.save_map;
  return stats;
}

void run_node(const Ros2Args& args) {
  SignalWatcher signals;  // first: a signal from now on ends the node cleanly
  const fs::path out_dir(args.output);
  const std::vector<fs::path> previous = previous_run_files(out_dir);
  if (!previous.empty() && !args.force) {
    throw Error("output folder " + out_dir.string() +
                " holds the outputs of an earlier run; choose another folder or pass --force to replace them");
  }
  if (!args.save_map.empty()) check_map_path(args.save_map, out_dir);
  const Settings settings = load_settings(args.config);
  set_opencv_threads(settings.segmentation.threads);

  ros2::LiveNodeOptions options;
  options.topics = input_topics(args, ros2::sensor_of(settings));
  options.input_qos = ros2::parse_qos_profile(args.qos, "--qos");
  options.pairing.tolerance_s = args.pair_tolerance;
  options.rectified_input = args.rectified_input;
  options.map_frame = args.map_frame;
  options.camera_frame = args.camera_frame;
  options.path_max_poses = args.path_max_poses;
  if (args.max_frames > 0) options.max_frames = args.max_frames;
  options.save_map = args.save_map;
  options.progress = ProgressOptions{.terminal = isatty(fileno(stderr)) != 0};
  options.check();
  ros2::DdsNetworkOptions network;
  network.domain = args.domain;
  network.loopback_only = !args.network;
  network.check();

  RunOptions viewer_hooks;
  const std::unique_ptr<RunViewer> viewer = start_run_viewer(args.viewer, settings, viewer_hooks, std::nullopt);
  options.pause = viewer_hooks.pause;
  options.on_start = viewer_hooks.on_start;
  options.on_end = viewer_hooks.on_end;

  SystemOptions system;
  system.use_segmentation = !args.no_segmentation;
  system.deterministic = args.deterministic;
  system.vocabulary_path = resolve_vocabulary_option(args.vocabulary);
  system.loop_closing = !args.no_loop_closing;
  system.trajectory_refinement.enabled = !args.raw_trajectory;

  prepare_output_folder(out_dir, previous);
  const ros2::DdsParticipant participant(network);
  spdlog::info("ros2: DDS domain {}, {}", args.domain, args.network ? "all interfaces" : "loopback only (127.0.0.1)");
  TrajectoryWriter live(out_dir / "trajectory_live.txt");
  const ros2::LiveNodeResult result = ros2::run_live_node(
      participant, settings, options, system, signals.stop(), [&](const FrameStats& f, const System& s) {
        for (const FrameStats::EarlierPose& p : f.start_frames_posed) live.write({p.timestamp, p.T_world_cam});
        if (f.has_pose) live.write({f.timestamp, *s.last_T_world_cam()});
      });

  const bool segmentation = system.use_segmentation && settings.segmentation.enabled;
  nlohmann::json stats = node_stats(args, options, result, signals, segmentation);
  const std::vector<std::string> write_errors = write_run_outputs(out_dir, result.run, stats);
  const RunSummary summary = summarize_run(result.run.frames);
  std::cout << "frames: " << summary.frames << ", tracked: " << summary.tracked << ", received "
            << result.received_first << " + " << result.received_second << " images, " << result.run.frames_in_input
            << " pairs, unpaired " << result.unpaired_first << " + " << result.unpaired_second << ", dropped stale "
            << result.dropped << ", poses published " << result.published_poses << "\n";
  if (write_errors.empty()) std::cout << "wrote " << (out_dir / "trajectory.txt").string() << ", stats.json\n";
  std::vector<std::string> errors = write_errors;
  if (result.run.map_file_error) errors.push_back(*result.run.map_file_error);
  if (result.run.error) errors.push_back(*result.run.error + " (the trajectory so far is in " + out_dir.string() + ")");
  for (std::size_t i = 0; i + 1 < errors.size(); ++i) spdlog::error("{}", errors[i]);
  if (!errors.empty()) throw Error(errors.back());
  if (result.run.interrupted) spdlog::info("ros2: stopped by {}; outputs written to {}", signal_name(signals.signal()), out_dir.string());
}

}  // namespace

void add_ros2_command(CLI::App& app) {
  auto args = std::make_shared<Ros2Args>();
  CLI::App* cmd = app.add_subcommand(
      "ros2", "live ROS 2 node (Cyclone DDS): images in, camera pose, path, TF, tracking state and mask out");
  cmd->add_option("--config", args->config, "settings YAML (stereo or RGB-D)")->required()->check(CLI::ExistingFile);
  ros2::add_image_topic_options(*cmd, args->images);
  cmd->add_option("--camera-info", args->camera_info, "CameraInfo topic checked once against the settings (default: the camera_info beside the left / colour "
                  "topic; 'none': not subscribed)");
  cmd->add_option("--output", args->output, "output folder (default ros2_output)");
  cmd->add_flag("--force", args->force, "replace an earlier run's outputs in --output");
  cmd->add_option("--domain", args->domain, "DDS domain (ROS_DOMAIN_ID), 0..232 (default 0)");
  cmd->add_flag("--network", args->network,
                "use every network interface with Cyclone's defaults (CYCLONEDDS_URI applies); default: loopback "
                "only, 127.0.0.1, no multicast");
  cmd->add_option("--qos", args->qos, "input QoS: default (reliable, keep last 10) or sensor_data (best effort, keep last 5)");
  cmd->add_option("--pair-tolerance", args->pair_tolerance, "largest stamp difference of a pair, seconds (default 0.01)");
  cmd->add_flag("--rectified-input", args->rectified_input,
                "the images are already rectified with the settings' raw stereo calibration (as ros2-replay "
                "publishes them); default: raw stereo settings mean raw images, rectified by the node");
  cmd->add_flag("--no-segmentation", args->no_segmentation, "same pipeline without dynamic masks");
  cmd->add_flag("--deterministic", args->deterministic, "synchronous local mapping (same input, same poses)");
  cmd->add_option("--vocabulary", args->vocabulary, "ORB vocabulary ('none' disables relocalization and loop closing)");
  cmd->add_flag("--no-loop-closing", args->no_loop_closing, "no loop detection/correction");
  cmd->add_flag("--raw-trajectory", args->raw_trajectory, "trajectory.txt as tracked, not re-estimated at the end");
  cmd->add_option("--save-map", args->save_map, "save every map to FILE at the end");
  cmd->add_option("--max-frames", args->max_frames, "stop after N processed frames (default: run until Ctrl-C)");
  cmd->add_option("--map-frame", args->map_frame, "frame id of the poses, path and TF parent (default map)");
  cmd->add_option("--camera-frame", args->camera_frame, "TF child and mask frame id (default camera)");
  cmd->add_option("--path-max-poses", args->path_max_poses, "newest poses kept in the published path (default 10000)");
  add_viewer_options(*cmd, args->viewer);
  cmd->footer(
      "Publishes stillslam/pose (geometry_msgs/PoseStamped), stillslam/path (nav_msgs/Path), tf "
      "(tf2_msgs/TFMessage map->camera), stillslam/tracking_state (std_msgs/String) and stillslam/dynamic_mask "
      "(sensor_msgs/Image mono8). Exit codes: 0 stopped by a signal or --max-frames, outputs written; 1 an error.");
  cmd->callback([args] { run_node(*args); });
}

}  // namespace stillslam::apps
