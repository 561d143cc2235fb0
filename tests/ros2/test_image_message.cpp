#include <gtest/gtest.h>

#include <vector>

#include "common/error_text.h"
#include "image_message.h"
#include "ros_time.h"

namespace stillslam::ros2 {
namespace {

TEST(ImageMessage, MaskIsMono8With255OnDynamicPixels) {
  cv::Mat1b mask = cv::Mat1b::zeros(4, 6);
  mask(1, 2) = 1;
  mask(3, 5) = 7;
  const cv::Mat1b image = mask_image(mask);
  const OutgoingImage out(image, 1403715273262142976LL, "camera");
  const sensor_msgs_msg_dds__Image_& m = out.message();
  EXPECT_STREQ(m.encoding, "mono8");
  EXPECT_STREQ(m.header.frame_id, "camera");
  EXPECT_EQ(m.header.stamp.sec, 1403715273);
  EXPECT_EQ(m.header.stamp.nanosec, 262142976u);
  EXPECT_EQ(m.width, 6u);
  EXPECT_EQ(m.height, 4u);
  EXPECT_EQ(m.step, 6u);
  EXPECT_EQ(m.is_bigendian, 0);
  ASSERT_EQ(m.data._length, 24u);
  std::vector<int> set;
  for (std::uint32_t i = 0; i < m.data._length; ++i) {
    if (m.data._buffer[i] != 0) {
      EXPECT_EQ(m.data._buffer[i], 255);
      set.push_back(static_cast<int>(i));
    }
  }
  EXPECT_EQ(set, (std::vector<int>{1 * 6 + 2, 3 * 6 + 5}));
}

TEST(ImageMessage, RoundTripsEveryPublishedType) {
  cv::Mat3b bgr(2, 3, cv::Vec3b(10, 20, 30));
  cv::Mat1w depth_mm(2, 3, static_cast<std::uint16_t>(1234));
  cv::Mat1f depth_m(2, 3, 1.5f);
  for (const cv::Mat& image : {cv::Mat(bgr), cv::Mat(depth_mm), cv::Mat(depth_m)}) {
    const OutgoingImage out(image, 0, "camera");
    const cv::Mat back = image_from_message(out.message(), "rt/x");
    ASSERT_EQ(back.type(), image.type());
    EXPECT_EQ(cv::norm(back, image, cv::NORM_INF), 0.0) << out.message().encoding;
  }
  EXPECT_STREQ(OutgoingImage(depth_mm, 0, "c").message().encoding, "16UC1");
  EXPECT_EQ(OutgoingImage(depth_m, 0, "c").message().step, 12u);
}

TEST(ImageMessage, Rgb8AndPaddedRowsBecomeBgr) {
  // rgb8 with 2 bytes of padding per row (step 8 for 2 pixels).
  std::vector<std::uint8_t> data = {1, 2, 3, 4, 5, 6, 0, 0, 7, 8, 9, 10, 11, 12, 0, 0};
  sensor_msgs_msg_dds__Image_ m{};
  char encoding[] = "rgb8";
  m.encoding = encoding;
  m.width = 2;
  m.height = 2;
  m.step = 8;
  m.data._length = m.data._maximum = static_cast<std::uint32_t>(data.size());
  m.data._buffer = data.data();
  const cv::Mat3b out = image_from_message(m, "rt/x");
  EXPECT_EQ(out(0, 0), cv::Vec3b(3, 2, 1));
  EXPECT_EQ(out(1, 1), cv::Vec3b(12, 11, 10));
}

TEST(ImageMessage, BadMessagesNameTheTopicAndTheFix) {
  std::vector<std::uint8_t> data(8, 0);
  sensor_msgs_msg_dds__Image_ m{};
  char yuv[] = "yuv422";
  char mono16[] = "16UC1";
  m.encoding = yuv;
  m.width = 2;
  m.height = 2;
  m.step = 4;
  m.data._length = m.data._maximum = 8;
  m.data._buffer = data.data();
  EXPECT_TRUE(test::contains(test::error_of([&] { image_from_message(m, "rt/cam"); }),
                             "rt/cam: image encoding 'yuv422' is not supported"));
  m.encoding = mono16;
  m.data._length = 6;  // too short for 2 rows of 4 bytes
  EXPECT_TRUE(test::contains(test::error_of([&] { image_from_message(m, "rt/cam"); }),
                             "rt/cam: image 2x2 '16UC1' with step 4 needs 8 bytes of data, the message has 6"));
}

TEST(ImageMessage, BigEndianDepthIsByteSwapped) {
  std::vector<std::uint8_t> data = {0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08};
  sensor_msgs_msg_dds__Image_ m{};
  char mono16[] = "16UC1";
  m.encoding = mono16;
  m.width = 2;
  m.height = 2;
  m.step = 4;
  m.is_bigendian = 1;
  m.data._length = m.data._maximum = 8;
  m.data._buffer = data.data();
  const cv::Mat1w out = image_from_message(m, "rt/depth");
  EXPECT_EQ(out(0, 0), 0x0102);
  EXPECT_EQ(out(1, 1), 0x0708);
}

TEST(RosTime, StampsSplitIntoSecondsAndNanoseconds) {
  const auto t = stamp_from_nanoseconds(1403715273262142976LL);
  EXPECT_EQ(stamp_nanoseconds(t), 1403715273262142976LL);
  const auto neg = stamp_from_nanoseconds(-1);
  EXPECT_EQ(neg.sec, -1);
  EXPECT_EQ(neg.nanosec, 999999999u);
  EXPECT_NEAR(seconds_from_nanoseconds(1403715273262142976LL), 1403715273.262143, 1e-6);
}

}  // namespace
}  // namespace stillslam::ros2
