// sensor_msgs Image / CompressedImage decoding: every supported encoding,
// row padding, byte order, PNG / JPEG / compressedDepth, and the errors for
// encodings not supported.
#include <gtest/gtest.h>

#include <cstring>

#include <opencv2/imgcodecs.hpp>

#include "stillslam/core/error.h"
#include "stillslam/io/ros2_image_convert.h"

namespace stillslam {
namespace {

ros2::Image raw(const std::string& encoding, std::uint32_t w, std::uint32_t h, std::uint32_t step,
                std::vector<std::uint8_t> data) {
  ros2::Image m;
  m.encoding = encoding;
  m.width = w;
  m.height = h;
  m.step = step;
  m.data = std::move(data);
  return m;
}

TEST(Ros2Image, ColourEncodingsComeOutBgr) {
  const cv::Mat rgb = ros2::image_to_mat(raw("rgb8", 1, 1, 3, {10, 20, 30}), "/c");
  EXPECT_EQ(rgb.at<cv::Vec3b>(0, 0), cv::Vec3b(30, 20, 10));
  const cv::Mat bgr = ros2::image_to_mat(raw("bgr8", 1, 1, 3, {10, 20, 30}), "/c");
  EXPECT_EQ(bgr.at<cv::Vec3b>(0, 0), cv::Vec3b(10, 20, 30));
  const cv::Mat bgra = ros2::image_to_mat(raw("bgra8", 1, 1, 4, {10, 20, 30, 255}), "/c");
  EXPECT_EQ(bgra.type(), CV_8UC3);
  EXPECT_EQ(bgra.at<cv::Vec3b>(0, 0), cv::Vec3b(10, 20, 30));
  const cv::Mat rgba = ros2::image_to_mat(raw("rgba8", 1, 1, 4, {10, 20, 30, 255}), "/c");
  EXPECT_EQ(rgba.at<cv::Vec3b>(0, 0), cv::Vec3b(30, 20, 10));
}

TEST(Ros2Image, StepPaddingAndByteOrder) {
  // 2x2 mono8 with 2 bytes of padding per row.
  const cv::Mat mono = ros2::image_to_mat(raw("mono8", 2, 2, 4, {1, 2, 99, 99, 3, 4, 99, 99}), "/m");
  EXPECT_EQ(mono.at<std::uint8_t>(1, 0), 3);
  EXPECT_EQ(mono.at<std::uint8_t>(1, 1), 4);
  // 16UC1 little endian 1000 mm, then big endian 1000 mm (0x03E8).
  const cv::Mat le = ros2::image_to_mat(raw("16UC1", 1, 1, 2, {0xE8, 0x03}), "/d");
  EXPECT_EQ(le.at<std::uint16_t>(0, 0), 1000);
  ros2::Image be = raw("16UC1", 1, 1, 2, {0x03, 0xE8});
  be.is_bigendian = 1;
  EXPECT_EQ(ros2::image_to_mat(be, "/d").at<std::uint16_t>(0, 0), 1000);
  const float metres = 1.25f;
  std::vector<std::uint8_t> f(4);
  std::memcpy(f.data(), &metres, 4);
  EXPECT_EQ(ros2::image_to_mat(raw("32FC1", 1, 1, 4, f), "/d").at<float>(0, 0), 1.25f);
}

TEST(Ros2Image, ShortDataAndUnknownEncodingAreErrors) {
  EXPECT_THROW(ros2::image_to_mat(raw("mono8", 4, 4, 4, {1, 2, 3}), "/m"), Error);
  try {
    ros2::image_to_mat(raw("bayer_rggb8", 1, 1, 1, {0}), "/camera/image_raw");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("/camera/image_raw"), std::string::npos) << m;
    EXPECT_NE(m.find("bayer_rggb8"), std::string::npos) << m;
    EXPECT_NE(m.find("mono8"), std::string::npos) << m;  // lists what is supported
  }
  ros2::CompressedImage tiff;
  tiff.format = "tiff";
  tiff.data = {1, 2, 3};
  EXPECT_THROW(ros2::compressed_image_to_mat(tiff, "/c"), Error);
}

TEST(Ros2Image, PngJpegAndCompressedDepthRoundTrip) {
  cv::Mat gray(6, 8, CV_8UC1);
  cv::randu(gray, 0, 255);
  const cv::Mat png = ros2::compressed_image_to_mat(ros2::mat_to_png(gray, {}), "/g");
  EXPECT_EQ(cv::norm(png, gray, cv::NORM_INF), 0);

  cv::Mat depth(6, 8, CV_16UC1);
  cv::randu(depth, 0, 10000);
  const ros2::CompressedImage cd = ros2::mat_to_png(depth, {});
  EXPECT_EQ(cd.format, "16UC1; compressedDepth png");
  const cv::Mat depth_back = ros2::compressed_image_to_mat(cd, "/d");
  ASSERT_EQ(depth_back.type(), CV_16UC1);
  EXPECT_EQ(cv::norm(depth_back, depth, cv::NORM_INF), 0);

  cv::Mat color(8, 8, CV_8UC3, cv::Scalar(200, 100, 50));
  ros2::CompressedImage jpeg;
  jpeg.format = "rgb8; jpeg compressed bgr8";
  cv::imencode(".jpg", color, jpeg.data);
  const cv::Mat jpeg_back = ros2::compressed_image_to_mat(jpeg, "/c");
  EXPECT_EQ(jpeg_back.type(), CV_8UC3);
  EXPECT_LT(cv::norm(jpeg_back, color, cv::NORM_INF), 4);

  ros2::CompressedImage broken = cd;
  broken.data.resize(20);
  EXPECT_THROW(ros2::compressed_image_to_mat(broken, "/d"), Error);
}

}  // namespace
}  // namespace stillslam
