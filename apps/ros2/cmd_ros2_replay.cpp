// `stillslam ros2-replay FOLDER`: publishes a dataset folder (TUM RGB-D,
// EuRoC, KITTI, or a `stillslam simulate` sequence) on ROS 2 topics at its
// timestamps (scaled by --rate), header stamps = the dataset's. The images
// are those stillslam's readers deliver: stereo pairs rectified (mono8; run
// the node with --rectified-input when the settings describe a raw pair),
// RGB-D colour bgr8 and depth 32FC1 in metres; each image topic gets a
// CameraInfo of the rectified camera beside it (.../camera_info). Waits for
// a subscriber on both image topics first. --lockstep waits, after each
// frame, for the node's tracking state of it: nothing is dropped however
// slow the node (tests, benchmarks).
#include <spdlog/spdlog.h>

#include <chrono>
#include <iostream>
#include <thread>

#include "camera_info_message.h"
#include "commands.h"
#include "dds.h"
#include "image_message.h"
#include "image_topic_args.h"
#include "ros_time.h"
#include "sensor_msgs/msg/CameraInfo.h"
#include "sensor_msgs/msg/Image.h"
#include "signal_watcher.h"
#include "std_msgs/msg/String.h"
#include "stillslam/core/error.h"
#include "stillslam/io/dataset.h"
#include "stillslam/settings/settings.h"

namespace stillslam::apps {
namespace {

using std::chrono::milliseconds;

struct ReplayArgs {
  ros2::ImageTopicArgs images;
  std::string folder, config, state_topic = "stillslam/tracking_state";
  std::string frame_id = "camera";
  double rate = 1.0, wait_subscriber = 10, lockstep_timeout = 60;
  int domain = 0;
  bool network = false, lockstep = false;
  std::size_t max_frames = 0;
};

milliseconds to_ms(double seconds) { return milliseconds(static_cast<long long>(seconds * 1000)); }

void replay(const ReplayArgs& args) {
  SignalWatcher signals;
  if (!(args.rate > 0 && args.rate <= 100)) throw Error(fmt::format("--rate {} is out of range (0, 100]", args.rate));
  const Settings settings = load_settings(args.config);
  const auto dataset = open_dataset(args.folder, settings);
  const bool stereo = dataset->sensor() == SensorType::Stereo;
  const auto [first, second] = ros2::image_topics(args.images, dataset->sensor(), args.folder);
  CameraCalibration camera = settings.camera;
  double baseline = 0;
  if (const auto rect = dataset->rectified_stereo()) {
    camera = rect->left;
    baseline = rect->baseline;
  }

  ros2::DdsNetworkOptions network;
  network.domain = args.domain;
  network.loopback_only = !args.network;
  const ros2::DdsParticipant participant(network);
  const ros2::DdsWriter<sensor_msgs_msg_dds__Image_> first_writer(participant, sensor_msgs_msg_dds__Image__desc, first);
  const ros2::DdsWriter<sensor_msgs_msg_dds__Image_> second_writer(participant, sensor_msgs_msg_dds__Image__desc, second);
  const ros2::DdsWriter<sensor_msgs_msg_dds__CameraInfo_> first_info(participant, sensor_msgs_msg_dds__CameraInfo__desc,
                                                                      ros2::camera_info_topic(first));
  const ros2::DdsWriter<sensor_msgs_msg_dds__CameraInfo_> second_info(
      participant, sensor_msgs_msg_dds__CameraInfo__desc, ros2::camera_info_topic(second));
  std::optional<ros2::DdsReader<std_msgs_msg_dds__String_>> state;
  if (args.lockstep) state.emplace(participant, std_msgs_msg_dds__String__desc, args.state_topic);

  const std::string where = " on DDS domain " + std::to_string(args.domain) + (args.network ? "" : " (loopback)");
  // The node's state topic first: the node creates its image readers before
  // its outputs, so other subscribers of the images (a viewer, a test) cannot
  // make the replay start before the node listens.
  for (const ros2::DdsEndpoint* e : {static_cast<const ros2::DdsEndpoint*>(state ? &*state : nullptr),
                                     static_cast<const ros2::DdsEndpoint*>(&first_writer),
                                     static_cast<const ros2::DdsEndpoint*>(&second_writer)}) {
    if (e == nullptr || args.wait_subscriber <= 0) continue;
    if (!e->wait_matched(1, to_ms(args.wait_subscriber))) {
      throw Error("no ROS 2 node matched " + e->name() + where + " within " + fmt::format("{}", args.wait_subscriber) +
                  " s (start `stillslam ros2` with the same --domain and --network, or raise --wait-subscriber)");
    }
  }
  // Matching is seen by the writer first; give the readers' side time to
  // match back, so the first frames are not sent to a reader that ignores them.
  if (args.wait_subscriber > 0) std::this_thread::sleep_for(milliseconds(500));

  std::size_t n = dataset->size();
  if (args.max_frames > 0) n = std::min(n, args.max_frames);
  spdlog::info("ros2-replay: {} frames of {} on {} and {}{}, rate {}", n, args.folder, ros2::dds_topic_name(first),
               ros2::dds_topic_name(second), where, args.rate);
  const auto start = std::chrono::steady_clock::now();
  std::size_t states = 0, sent = 0;
  for (std::size_t i = 0; i < n && !signals.stop(); ++i) {
    const double due = (dataset->timestamp(i) - dataset->timestamp(0)) / args.rate;
    std::this_thread::sleep_until(start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                              std::chrono::duration<double>(due)));
    const SensorFrame frame = dataset->load(i);
    const std::int64_t stamp = ros2::nanoseconds_from_seconds(dataset->timestamp(i));
    const ros2::OutgoingImage a(stereo ? frame.gray : frame.color, stamp, args.frame_id);
    const ros2::OutgoingImage b(stereo ? frame.right : frame.depth, stamp, args.frame_id);
    const ros2::OutgoingCameraInfo ia(camera, 0, stamp, args.frame_id);
    const ros2::OutgoingCameraInfo ib(camera, stereo ? baseline : 0, stamp, args.frame_id);
    first_info.write(ia.message());
    second_info.write(ib.message());
    first_writer.write(a.message());
    second_writer.write(b.message());
    ++sent;
    if (!state) continue;
    // The node sends one tracking state per frame it processed.
    const auto deadline = std::chrono::steady_clock::now() + to_ms(args.lockstep_timeout);
    while (states < sent && !signals.stop()) {
      states += state->take([](const std_msgs_msg_dds__String_&) {});
      if (states >= sent) break;
      if (std::chrono::steady_clock::now() > deadline) {
        throw Error("ros2-replay --lockstep: no tracking state on " + state->name() + " for frame " +
                    std::to_string(i) + " within " + fmt::format("{}", args.lockstep_timeout) + " s");
      }
      std::this_thread::sleep_for(milliseconds(2));
    }
  }
  for (const ros2::DdsEndpoint* w : {static_cast<const ros2::DdsEndpoint*>(&first_writer),
                                     static_cast<const ros2::DdsEndpoint*>(&second_writer)}) {
    if (!w->wait_for_acks(milliseconds(5000))) spdlog::warn("ros2-replay: {} not acknowledged by every reader", w->name());
  }
  std::cout << "published " << sent << " frames of " << n << (signals.stop() ? " (stopped by a signal)" : "") << "\n";
}

}  // namespace

void add_ros2_replay_command(CLI::App& app) {
  auto args = std::make_shared<ReplayArgs>();
  CLI::App* cmd = app.add_subcommand("ros2-replay", "publish a dataset folder on ROS 2 topics at its timestamps");
  cmd->add_option("folder", args->folder, "dataset folder (TUM RGB-D, EuRoC, KITTI, simulated)")->required();
  cmd->add_option("--config", args->config, "settings YAML of the dataset")->required()->check(CLI::ExistingFile);
  cmd->add_option("--rate", args->rate, "speed factor: 0.5 = half speed (default 1)");
  ros2::add_image_topic_options(*cmd, args->images);
  cmd->add_option("--frame-id", args->frame_id, "header frame id of the images (default camera)");
  cmd->add_option("--domain", args->domain, "DDS domain (ROS_DOMAIN_ID), default 0");
  cmd->add_flag("--network", args->network, "every network interface (default: loopback only)");
  cmd->add_option("--wait-subscriber", args->wait_subscriber,
                  "seconds to wait for a subscriber on both image topics before publishing (default 10; 0: do not wait)");
  cmd->add_flag("--lockstep", args->lockstep,
                "after each frame wait for the node's tracking state (no frame is dropped however slow the node)");
  cmd->add_option("--lockstep-timeout", args->lockstep_timeout, "seconds to wait for each state (default 60)");
  cmd->add_option("--state-topic", args->state_topic, "the node's tracking state topic (default stillslam/tracking_state)");
  cmd->add_option("--max-frames", args->max_frames, "publish at most N frames");
  cmd->callback([args] { replay(*args); });
}

}  // namespace stillslam::apps
