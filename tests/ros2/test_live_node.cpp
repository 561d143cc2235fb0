// run_live_node in this process, fed by writers in the test: a bad input
// message ends the run with an error naming the topic and the fix, after the
// System shut down cleanly; the viewer's hooks see the System, a paused gate
// holds the node (images keep arriving and are dropped as stale), a step lets
// exactly one pair through, and on_end runs before the System goes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "common/error_text.h"
#include "image_message.h"
#include "live_node.h"
#include "stillslam/settings/settings.h"

namespace stillslam::ros2 {
namespace {

using namespace std::chrono_literals;

// A stereo node on topics PREFIX/left, PREFIX/right in a domain of its own
// (derived from the process id, so tests running side by side never meet).
struct InProcessNode {
  InProcessNode(const std::string& prefix, int first_domain)
      : settings(load_settings(std::string(STILLSLAM_SOURCE_DIR) + "/config/euroc.yaml")),
        participant(network_of(first_domain)) {
    options.topics.first = prefix + "/left";
    options.topics.second = prefix + "/right";
    options.rectified_input = true;
    system.use_segmentation = false;
  }
  static DdsNetworkOptions network_of(int first_domain) {
    DdsNetworkOptions network;
    network.domain = first_domain + static_cast<int>(::getpid() % 40);
    return network;
  }
  void start() {
    thread = std::thread([this] { result = run_live_node(participant, settings, options, system, stop, {}); });
  }
  void finish() {
    stop = true;
    if (thread.joinable()) thread.join();
  }
  ~InProcessNode() { finish(); }  // a failed ASSERT returns early

  Settings settings;
  DdsParticipant participant;
  LiveNodeOptions options;
  SystemOptions system;
  std::atomic<bool> stop{false};
  LiveNodeResult result;
  std::thread thread;
};

TEST(LiveNode, AnUnsupportedEncodingEndsTheRunWithAClearError) {
  InProcessNode node("test", 141);
  node.start();
  const DdsWriter<sensor_msgs_msg_dds__Image_> left(node.participant, sensor_msgs_msg_dds__Image__desc, "test/left");
  ASSERT_TRUE(left.wait_matched(1, 20s));
  const OutgoingImage image(cv::Mat1b(480, 752, uchar{0}), 1000, "camera");
  sensor_msgs_msg_dds__Image_ message = image.message();
  char yuv[] = "yuv422";
  message.encoding = yuv;
  left.write(message);
  for (int i = 0; i < 2000 && !node.result.run.error; ++i) std::this_thread::sleep_for(10ms);
  node.finish();  // ends the node whatever happened (the test then fails below)
  const LiveNodeResult& result = node.result;
  ASSERT_TRUE(result.run.error.has_value());
  EXPECT_TRUE(test::contains(*result.run.error, "rt/test/left: image encoding 'yuv422' is not supported (supported: mono8"))
      << *result.run.error;
  EXPECT_EQ(result.run.end, RunEnd::InputError);
  EXPECT_EQ(result.received_first, 1u);
  EXPECT_TRUE(result.run.frames.empty());
}

TEST(LiveNode, PauseGateHoldsTheNodeAndHooksSeeTheSystem) {
  PauseGate gate;  // declared first: outlives the node's thread
  gate.pause();
  int starts = 0, ends = 0;
  std::size_t keyframes_at_start = 99;
  InProcessNode node("hooks", 181);
  LiveNodeOptions& options = node.options;
  options.topics.camera_info.clear();
  options.pause = &gate;
  options.on_start = [&](const System& s) {
    ++starts;
    keyframes_at_start = s.num_keyframes();
  };
  options.on_end = [&] { ++ends; };
  node.start();

  const DdsWriter<sensor_msgs_msg_dds__Image_> left(node.participant, sensor_msgs_msg_dds__Image__desc, "hooks/left");
  const DdsWriter<sensor_msgs_msg_dds__Image_> right(node.participant, sensor_msgs_msg_dds__Image__desc, "hooks/right");
  ASSERT_TRUE(left.wait_matched(1, 20s));
  ASSERT_TRUE(right.wait_matched(1, 20s));
  const cv::Mat1b blank(480, 752, uchar{128});
  const auto send = [&](std::int64_t stamp_ns) {
    const OutgoingImage l(blank, stamp_ns, "camera"), r(blank, stamp_ns, "camera");
    left.write(l.message());
    right.write(r.message());
  };
  for (int i = 0; i < 3; ++i) {  // paused: none of these is processed
    send(1'000'000'000LL + i * 50'000'000LL);
    std::this_thread::sleep_for(100ms);
  }
  EXPECT_EQ(gate.passed(), 0u);
  gate.step();  // one pair through: the newest waiting one
  for (int i = 0; i < 300 && gate.passed() == 0; ++i) std::this_thread::sleep_for(10ms);
  std::this_thread::sleep_for(300ms);
  node.finish();
  const LiveNodeResult& result = node.result;
  EXPECT_EQ(starts, 1);
  EXPECT_EQ(ends, 1);
  EXPECT_EQ(keyframes_at_start, 0u);
  EXPECT_EQ(gate.passed(), 1u);
  EXPECT_EQ(result.run.frames.size(), 1u);
  EXPECT_EQ(result.run.frames_in_input, 3u);
  EXPECT_EQ(result.dropped, 2u);  // the two older pairs were replaced while the gate held
}

}  // namespace
}  // namespace stillslam::ros2
