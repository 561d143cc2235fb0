// CDR (XCDR1) reading and writing of the ROS 2 messages stillslam uses:
// round trips, a hand-made big-endian payload, and errors on short data.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>

#include "stillslam/core/error.h"
#include "stillslam/io/cdr_reader.h"
#include "stillslam/io/cdr_writer.h"
#include "stillslam/io/ros2_message_codec.h"
#include "stillslam/io/ros2_message_definitions.h"

namespace stillslam {
namespace {

using ros2::Bytes;

TEST(Cdr, WriterAlignsFromTheEndOfTheHeader) {
  CdrWriter w;
  w.u8(7);
  w.f64(1.5);
  w.string("ab");
  const Bytes& b = w.data();
  // header 4 + u8 1 + pad 7 + f64 8 + len 4 + "ab\0" 3
  ASSERT_EQ(b.size(), 27u);
  EXPECT_EQ(b[1], 1);  // little endian
  double v;
  std::memcpy(&v, b.data() + 12, 8);
  EXPECT_EQ(v, 1.5);
  EXPECT_EQ(b[20], 3);
  CdrReader r(b.data(), b.size(), "test");
  EXPECT_EQ(r.u8(), 7);
  EXPECT_EQ(r.f64(), 1.5);
  EXPECT_EQ(r.string(), "ab");
}

TEST(Cdr, OdometryAndTfRoundTrip) {
  ros2::Odometry odom;
  odom.header.set_stamp_ns(1'700'000'000'123'456'789);
  odom.header.frame_id = "odom";
  odom.child_frame_id = "base_link";
  odom.pose.position = {1, 2, 3};
  odom.pose.orientation = {0, 0, std::sqrt(0.5), std::sqrt(0.5)};
  odom.pose_covariance[35] = 0.25;
  odom.angular = {0, 0, 0.5};
  const ros2::Odometry back = ros2::decode_odometry(ros2::encode(odom), "odom");
  EXPECT_EQ(back.header.stamp_ns(), 1'700'000'000'123'456'789);
  EXPECT_EQ(back.header.frame_id, "odom");
  EXPECT_EQ(back.child_frame_id, "base_link");
  EXPECT_EQ(back.pose.position, odom.pose.position);
  EXPECT_EQ(back.pose.orientation, odom.pose.orientation);
  EXPECT_EQ(back.pose_covariance[35], 0.25);
  EXPECT_EQ(back.angular[2], 0.5);

  ros2::TfMessage tf;
  tf.transforms.resize(2);
  tf.transforms[0].header.frame_id = "map";
  tf.transforms[0].child_frame_id = "odom";
  tf.transforms[1].header.frame_id = "odom";
  tf.transforms[1].child_frame_id = "base_footprint";
  tf.transforms[1].transform.position = {0.5, -1, 0};
  const ros2::TfMessage tf_back = ros2::decode_tf_message(ros2::encode(tf), "/tf");
  ASSERT_EQ(tf_back.transforms.size(), 2u);
  EXPECT_EQ(tf_back.transforms[1].child_frame_id, "base_footprint");
  EXPECT_EQ(tf_back.transforms[1].transform.position[1], -1);
}

TEST(Cdr, CameraInfoImageAndCompressedRoundTrip) {
  ros2::CameraInfo info;
  info.width = 752;
  info.height = 480;
  info.distortion_model = "plumb_bob";
  info.d = {-0.28, 0.07, 0.0002, 0.00002, 0};
  info.k = {458.654, 0, 367.215, 0, 457.296, 248.375, 0, 0, 1};
  info.p[3] = -50.4;
  info.roi_do_rectify = true;
  const ros2::CameraInfo back = ros2::decode_camera_info(ros2::encode(info), "info");
  EXPECT_EQ(back.d, info.d);
  EXPECT_EQ(back.k, info.k);
  EXPECT_EQ(back.p[3], -50.4);
  EXPECT_EQ(back.width, 752u);
  EXPECT_TRUE(back.roi_do_rectify);

  ros2::Image image;
  image.width = 3;
  image.height = 2;
  image.encoding = "mono8";
  image.step = 4;
  image.data = {1, 2, 3, 0, 4, 5, 6, 0};
  const ros2::Image image_back = ros2::decode_image(ros2::encode(image), "img");
  EXPECT_EQ(image_back.step, 4u);
  EXPECT_EQ(image_back.data, image.data);
  EXPECT_EQ(image_back.encoding, "mono8");
  EXPECT_EQ(ros2::decode_stamp_ns(ros2::encode(image), "img"), 0);

  ros2::CompressedImage c;
  c.format = "png";
  c.data = {9, 8, 7};
  EXPECT_EQ(ros2::decode_compressed_image(ros2::encode(c), "c").data, c.data);
}

TEST(Cdr, ReadsBigEndianPoseStamped) {
  Bytes b = {0x00, 0x00, 0x00, 0x00};  // CDR_BE
  const auto u32 = [&](std::uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) b.push_back(static_cast<std::uint8_t>(v >> s));
  };
  const auto f64 = [&](double d) {
    const auto v = std::bit_cast<std::uint64_t>(d);
    for (int s = 56; s >= 0; s -= 8) b.push_back(static_cast<std::uint8_t>(v >> s));
  };
  u32(12);          // sec
  u32(500000000);   // nanosec
  u32(4);           // "map\0"
  for (char ch : std::string("map")) b.push_back(static_cast<std::uint8_t>(ch));
  b.push_back(0);
  // body offset 16: already 8-aligned
  for (double d : {1.0, -2.0, 3.5, 0.0, 0.0, 0.0, 1.0}) f64(d);
  const ros2::PoseStamped p = ros2::decode_pose_stamped(b, "pose");
  EXPECT_EQ(p.header.sec, 12);
  EXPECT_EQ(p.header.nanosec, 500000000u);
  EXPECT_EQ(p.header.frame_id, "map");
  EXPECT_EQ(p.pose.position[1], -2.0);
  EXPECT_EQ(p.pose.position[2], 3.5);
  EXPECT_EQ(p.pose.orientation[3], 1.0);
}

TEST(Cdr, ShortOrCorruptPayloadsAreErrorsNamingTheMessage) {
  ros2::Odometry odom;
  Bytes b = ros2::encode(odom);
  b.resize(b.size() - 5);
  try {
    ros2::decode_odometry(b, "topic /odom message 3");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("topic /odom message 3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("at byte"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ros2::decode_odometry(Bytes{0, 1}, "x"), Error);
  EXPECT_THROW(ros2::decode_odometry(Bytes{0, 2, 0, 0}, "x"), Error);  // PL_CDR
  // A sequence count past the end fails before allocating.
  CdrWriter w;
  w.u32(0xFFFFFFF0u);
  EXPECT_THROW(ros2::decode_tf_message(w.data(), "tf"), Error);
}

TEST(Ros2Definitions, NestedTypesOnceInDependencyOrder) {
  const std::string odom = ros2::message_definition(ros2::kOdometryType);
  EXPECT_EQ(odom.rfind("std_msgs/Header header\nstring child_frame_id\n", 0), 0u) << odom;
  for (const char* nested : {"MSG: geometry_msgs/PoseWithCovariance\n", "MSG: geometry_msgs/Pose\n",
                             "MSG: geometry_msgs/Quaternion\n", "MSG: builtin_interfaces/Time\n",
                             "MSG: geometry_msgs/Vector3\n"}) {
    const auto at = odom.find(nested);
    ASSERT_NE(at, std::string::npos) << nested;
    EXPECT_EQ(odom.find(nested, at + 1), std::string::npos) << nested << " twice";
  }
  EXPECT_NE(ros2::message_definition(ros2::kCameraInfoType).find("MSG: sensor_msgs/RegionOfInterest\n"),
            std::string::npos);
  EXPECT_TRUE(ros2::message_definition("foo_msgs/msg/Bar").empty());
}

}  // namespace
}  // namespace stillslam
