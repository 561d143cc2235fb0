#include "live_node.h"

#include <spdlog/spdlog.h>

#include "frame_assembler.h"
#include "frame_stamps.h"
#include "image_receiver.h"
#include "snapshot_publisher.h"
#include "stillslam/core/error.h"
#include "stillslam/core/mailbox.h"
#include "stillslam/core/scope_exit.h"
#include "stillslam/core/stopwatch.h"

namespace stillslam::ros2 {

void LiveNodeOptions::check() const {
  pairing.check();
  if (topics.first.empty() || topics.second.empty()) throw Error("the ROS 2 node needs two image topics");
  if (topics.first == topics.second) {
    throw Error("both image topics are '" + topics.first + "': give two different topics");
  }
  if (map_frame.empty() || camera_frame.empty()) throw Error("--map-frame and --camera-frame must not be empty");
  if (path_max_poses == 0) throw Error("--path-max-poses must be at least 1");
}

LiveNodeResult run_live_node(const DdsParticipant& participant, const Settings& settings,
                             const LiveNodeOptions& options, const SystemOptions& system_options,
                             const std::atomic<bool>& stop,
                             const std::function<void(const FrameStats&, const System&)>& on_frame) {
  options.check();
  LiveNodeResult out;
  Stopwatch wall;
  const FrameAssembler assembler(settings, options.rectified_input);
  System system(settings, assembler.sensor(), assembler.rectified_stereo(), system_options);
  if (options.on_start) options.on_start(system);
  const ScopeExit end_notice(options.on_end);  // before `system` is destroyed, however this function leaves
  FrameStamps stamps;
  Mailbox<SensorFrame> mailbox;
  {
    // Readers first: a peer that sees the node's outputs matched knows its
    // inputs exist too (ros2-replay --lockstep waits for the state topic).
    ImageReceiver receiver(participant, options, assembler, mailbox, stamps, stop);
    SnapshotPublisher publisher(participant, system.publisher(), stamps, options.topics, options.map_frame,
                                options.camera_frame, options.path_max_poses);
    std::optional<ProgressReporter> progress;
    if (options.progress) progress.emplace(system.publisher(), *options.progress);
    spdlog::info("ros2: listening on {} and {} ({})", dds_topic_name(options.topics.first),
                 dds_topic_name(options.topics.second), to_string(assembler.sensor()));
    try {
      while (!options.max_frames || out.run.frames.size() < *options.max_frames) {
        if (options.pause != nullptr && !options.pause->wait(&stop)) break;
        std::optional<SensorFrame> frame = mailbox.take();
        if (!frame) break;
        FrameStats stats = system.process(*frame);
        mark_start_frames_posed(out.run.frames, stats);
        if (on_frame) on_frame(stats, system);
        out.run.frames.push_back(std::move(stats));
      }
    } catch (const Error& e) {
      out.run.error = e.what();
    }
    receiver.stop();
    publisher.stop();
    if (progress) progress->stop();
    if (!out.run.error) out.run.error = receiver.error();
    out.received_first = receiver.received_first();
    out.received_second = receiver.received_second();
    out.unpaired_first = receiver.pairer().unpaired_first();
    out.unpaired_second = receiver.pairer().unpaired_second();
    out.run.frames_in_input = receiver.pairer().pairs();
    out.camera_info_messages = receiver.camera_infos();
    out.published_poses = publisher.published_poses();
  }
  out.dropped = mailbox.skipped();
  out.run.dropped_frames = out.dropped;
  out.run.interrupted = stop.load();
  system.shutdown();
  if (!options.save_map.empty()) {
    try {
      Stopwatch save;
      out.run.map_file = system.save_map(options.save_map);
      out.run.save_map_ms = save.elapsed_ms();
    } catch (const Error& e) {
      out.run.map_file_error = e.what();
    }
  }
  collect_system_results(system, out.run);
  if (out.run.error) {
    out.run.end = RunEnd::InputError;
  } else if (out.run.interrupted) {
    out.run.end = RunEnd::Interrupted;
  } else {
    out.run.end = RunEnd::MaxFrames;
  }
  out.run.wall_seconds = wall.elapsed_ms() / 1000.0;
  return out;
}

}  // namespace stillslam::ros2
