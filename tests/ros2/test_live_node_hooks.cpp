// run_live_node's viewer hooks in this process: on_start sees the System, a
// paused gate holds the node (images keep arriving and are dropped as stale),
// a step lets exactly one pair through, and on_end runs before the System goes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "image_message.h"
#include "live_node.h"
#include "stillslam/settings/settings.h"

namespace stillslam::ros2 {
namespace {

using namespace std::chrono_literals;

TEST(LiveNode, PauseGateHoldsTheNodeAndHooksSeeTheSystem) {
  const Settings settings = load_settings(std::string(STILLSLAM_SOURCE_DIR) + "/config/euroc.yaml");
  DdsNetworkOptions network;
  network.domain = 181 + static_cast<int>(::getpid() % 40);  // each test its own range of domains
  const DdsParticipant participant(network);
  PauseGate gate;
  gate.pause();
  int starts = 0, ends = 0;
  std::size_t keyframes_at_start = 99;
  LiveNodeOptions options;
  options.topics.first = "hooks/left";
  options.topics.second = "hooks/right";
  options.topics.camera_info.clear();
  options.rectified_input = true;
  options.pause = &gate;
  options.on_start = [&](const System& s) {
    ++starts;
    keyframes_at_start = s.num_keyframes();
  };
  options.on_end = [&] { ++ends; };
  SystemOptions system;
  system.use_segmentation = false;
  std::atomic<bool> stop{false};
  LiveNodeResult result;
  std::thread node([&] { result = run_live_node(participant, settings, options, system, stop, {}); });

  const DdsWriter<sensor_msgs_msg_dds__Image_> left(participant, sensor_msgs_msg_dds__Image__desc, "hooks/left");
  const DdsWriter<sensor_msgs_msg_dds__Image_> right(participant, sensor_msgs_msg_dds__Image__desc, "hooks/right");
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
  stop = true;
  node.join();
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
