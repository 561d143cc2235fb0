// run_live_node in this process: a bad input message ends the run with an
// error naming the topic and the fix, after the System shut down cleanly.
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

TEST(LiveNode, AnUnsupportedEncodingEndsTheRunWithAClearError) {
  const Settings settings = load_settings(std::string(STILLSLAM_SOURCE_DIR) + "/config/euroc.yaml");
  DdsNetworkOptions network;
  network.domain = 141 + static_cast<int>(::getpid() % 40);  // each test its own range of domains
  const DdsParticipant participant(network);
  LiveNodeOptions options;
  options.topics.first = "test/left";
  options.topics.second = "test/right";
  options.rectified_input = true;
  SystemOptions system;
  system.use_segmentation = false;
  std::atomic<bool> stop{false};
  LiveNodeResult result;
  std::thread node([&] { result = run_live_node(participant, settings, options, system, stop, {}); });

  const DdsWriter<sensor_msgs_msg_dds__Image_> left(participant, sensor_msgs_msg_dds__Image__desc, "test/left");
  ASSERT_TRUE(left.wait_matched(1, 20s));
  const OutgoingImage image(cv::Mat1b(480, 752, uchar{0}), 1000, "camera");
  sensor_msgs_msg_dds__Image_ message = image.message();
  char yuv[] = "yuv422";
  message.encoding = yuv;
  left.write(message);
  for (int i = 0; i < 2000 && !result.run.error; ++i) std::this_thread::sleep_for(10ms);
  stop = true;  // ends the node whatever happened (the test then fails below)
  node.join();
  ASSERT_TRUE(result.run.error.has_value());
  EXPECT_TRUE(test::contains(*result.run.error, "rt/test/left: image encoding 'yuv422' is not supported (supported: mono8"))
      << *result.run.error;
  EXPECT_EQ(result.run.end, RunEnd::InputError);
  EXPECT_EQ(result.received_first, 1u);
  EXPECT_TRUE(result.run.frames.empty());
}

}  // namespace
}  // namespace stillslam::ros2
