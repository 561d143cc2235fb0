#include <gtest/gtest.h>
#include <unistd.h>

#include <thread>

#include "common/error_text.h"
#include "cyclone_config.h"
#include "dds.h"
#include "std_msgs/msg/String.h"

namespace stillslam::ros2 {
namespace {

TEST(CycloneConfig, LoopbackOnlyBindsLocalhostWithoutMulticast) {
  DdsNetworkOptions options;
  const auto xml = cyclone_config_xml(options);
  ASSERT_TRUE(xml);
  EXPECT_TRUE(test::contains(*xml, "<NetworkInterface address=\"127.0.0.1\"/>"));
  EXPECT_TRUE(test::contains(*xml, "<AllowMulticast>false</AllowMulticast>"));
  EXPECT_TRUE(test::contains(*xml, "<Peers><Peer address=\"127.0.0.1\"/></Peers>"));
  EXPECT_TRUE(test::contains(*xml, "<MaxAutoParticipantIndex>31</MaxAutoParticipantIndex>"));
  EXPECT_EQ(xml->find("192."), std::string::npos);
}

TEST(CycloneConfig, NetworkModeLeavesCycloneDefaults) {
  DdsNetworkOptions options;
  options.loopback_only = false;
  EXPECT_FALSE(cyclone_config_xml(options));
}

TEST(CycloneConfig, RejectsDomainOutOfRange) {
  DdsNetworkOptions options;
  options.domain = 233;
  EXPECT_TRUE(test::contains(test::error_of([&] { options.check(); }), "--domain 233 is out of range"));
}

TEST(DdsTopics, RosNamesGetTheRtPrefix) {
  EXPECT_EQ(dds_topic_name("/camera/left/image_raw"), "rt/camera/left/image_raw");
  EXPECT_EQ(dds_topic_name("tf"), "rt/tf");
  EXPECT_EQ(camera_info_topic("/zed/zed_node/left/image_rect_color"), "/zed/zed_node/left/camera_info");
  EXPECT_EQ(camera_info_topic("image"), "camera_info");
  EXPECT_TRUE(test::contains(test::error_of([] { dds_topic_name("/"); }), "empty ROS 2 topic name"));
  EXPECT_EQ(parse_qos_profile("sensor_data", "--qos"), QosProfile::SensorData);
  EXPECT_TRUE(test::contains(test::error_of([] { parse_qos_profile("fast", "--qos"); }), "--qos 'fast'"));
}

// Two participants in two domains would need two processes; one participant
// with a writer and a reader shows the loopback configuration carries data.
TEST(DdsParticipant, LoopbackConfigurationDeliversMessages) {
  DdsNetworkOptions options;
  options.domain = 181 + static_cast<int>(::getpid() % 20);  // each test its own range of domains
  const DdsParticipant participant(options);
  const DdsWriter<std_msgs_msg_dds__String_> writer(participant, std_msgs_msg_dds__String__desc, "/test/state");
  const DdsReader<std_msgs_msg_dds__String_> reader(participant, std_msgs_msg_dds__String__desc, "test/state");
  ASSERT_TRUE(writer.wait_matched(1, std::chrono::seconds(10)));
  char text[] = "ok";
  writer.write(std_msgs_msg_dds__String_{text});
  std::string got;
  DdsWaiter waiter(participant);
  waiter.add(reader);
  for (int i = 0; i < 100 && got.empty(); ++i) {
    waiter.wait(std::chrono::milliseconds(100));
    reader.take([&](const std_msgs_msg_dds__String_& m) { got = m.data; });
  }
  EXPECT_EQ(got, "ok");
}

}  // namespace
}  // namespace stillslam::ros2
