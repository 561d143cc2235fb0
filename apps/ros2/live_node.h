#pragma once
// The live ROS 2 node: subscribes to two image topics (stereo left/right or
// RGB-D colour/depth) and optionally a CameraInfo topic, pairs them by header
// stamp, and feeds the System from the calling thread through a latest-value
// mailbox: when the System is busy, a newer pair replaces the waiting one
// (counted as dropped), so the node keeps up with the camera and memory stays
// bounded. A publishing thread takes the System's frame snapshots (publish
// layer) and sends the camera pose, TF, the path, the tracking state and the
// dynamic mask.
//
// Threads: receive (DDS waitset -> pairer -> mailbox), process (the caller:
// mailbox -> System::process), publish (snapshots -> DDS). Each stops on the
// stop flag, at --max-frames, or at the first input error.
#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "dds.h"
#include "stamp_pairer.h"
#include "stillslam/system/dataset_runner.h"
#include "stillslam/system/pause_gate.h"
#include "stillslam/system/progress.h"

namespace stillslam::ros2 {

// The node's topics, relative ROS 2 names (DDS adds "rt/").
struct NodeTopics {
  std::string first, second;  // left/right or rgb/depth
  std::string camera_info;    // empty: not subscribed
  std::string pose = "stillslam/pose";
  std::string path = "stillslam/path";
  std::string tf = "tf";
  std::string state = "stillslam/tracking_state";
  std::string mask = "stillslam/dynamic_mask";
};

struct LiveNodeOptions {
  NodeTopics topics;
  QosProfile input_qos = QosProfile::Default;
  PairingOptions pairing;
  bool rectified_input = false;  // see FrameAssembler
  std::string map_frame = "map";
  std::string camera_frame = "camera";
  std::size_t path_max_poses = 10000;
  std::optional<std::size_t> max_frames;
  std::filesystem::path save_map;
  std::optional<ProgressOptions> progress;  // a progress line on stderr while it runs
  // The viewer (--viewer): waited on before each pair is taken (pairs that
  // arrive while paused replace each other in the mailbox, counted as
  // dropped); on_start gets the System once built, on_end runs before it is
  // destroyed.
  PauseGate* pause = nullptr;
  std::function<void(const System&)> on_start;
  std::function<void()> on_end;
  void check() const;
};

struct LiveNodeResult {
  RunResult run;  // frames, trajectory, stats; frames_in_input = pairs made
  std::size_t received_first = 0, received_second = 0;
  std::size_t unpaired_first = 0, unpaired_second = 0;
  std::size_t dropped = 0;  // pairs replaced in the mailbox before the System took them
  std::size_t published_poses = 0;
  std::size_t camera_info_messages = 0;
};

// Runs until `stop` is set, max_frames pairs are processed, or an input
// error; then shuts the System down and collects its results (the error, if
// any, in run.error). Construction errors (settings, DDS) throw.
LiveNodeResult run_live_node(const DdsParticipant& participant, const Settings& settings,
                             const LiveNodeOptions& options, const SystemOptions& system_options,
                             const std::atomic<bool>& stop,
                             const std::function<void(const FrameStats&, const System&)>& on_frame);

}  // namespace stillslam::ros2
