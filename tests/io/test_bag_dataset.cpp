// BagDataset on small synthetic bags: stereo pairing by header stamp with
// unpaired counts, RGB-D depth units, side-by-side splitting, CameraInfo
// calibration, and the errors for a missing topic, one camera topic, and an
// unknown encoding.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include <opencv2/imgproc.hpp>

#include "io/temp_dir.h"
#include "stillslam/core/error.h"
#include "stillslam/io/bag_camera_info.h"
#include "stillslam/io/bag_dataset.h"
#include "stillslam/io/bag_trajectory.h"
#include "stillslam/io/bag_writer.h"
#include "stillslam/io/dataset.h"
#include "stillslam/io/ros2_image_convert.h"
#include "stillslam/io/ros2_message_codec.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;
constexpr std::int64_t kStart = 1'700'000'000'000'000'000;
constexpr std::int64_t kPeriod = 50'000'000;  // 20 Hz

cv::Mat pattern(int w, int h, int seed) {
  cv::Mat m(h, w, CV_8UC1);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) m.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>((x * 7 + y * 3 + seed * 11) % 251);
  }
  return m;
}

ros2::Header header(std::int64_t ns) {
  ros2::Header h;
  h.set_stamp_ns(ns);
  return h;
}

CameraSettings rectified_stereo_settings() {
  CameraSettings s;
  s.camera = pinhole_calibration(30, 30, 16, 12, 32, 24);
  StereoCalibration st;
  st.left = st.right = s.camera;
  st.baseline = 0.1;
  st.T_c1_c2.translation() = Eigen::Vector3d(0.1, 0, 0);
  st.rectified = true;
  s.stereo = st;
  s.bf = 3;
  return s;
}

// 6 left frames, 5 right frames 1 ms later (the last left one has no
// partner), written right-first and out of order to test the sorting.
fs::path write_stereo_bag(const fs::path& dir, const std::string& out, const std::string& right_encoding = "mono8") {
  auto bag = open_bag_writer(dir / out, BagWriterOptions{});
  const auto l = bag->add_topic("/left/image_raw", ros2::kImageType);
  const auto r = bag->add_topic("/right/image_raw", ros2::kImageType);
  bag->add_topic("/imu", "sensor_msgs/msg/Imu");
  for (int k = 4; k >= 0; --k) {
    ros2::Image img = ros2::mat_to_image(pattern(32, 24, 100 + k), header(kStart + k * kPeriod + 1'000'000));
    img.encoding = right_encoding;
    bag->write(r, kStart + k * kPeriod, ros2::encode(img));
  }
  for (int k = 0; k < 6; ++k) {
    bag->write(l, kStart + k * kPeriod, ros2::encode(ros2::mat_to_image(pattern(32, 24, k), header(kStart + k * kPeriod))));
  }
  bag->close();
  return dir / out;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(BagDataset, StereoPairsByHeaderStampAndCountsUnpaired) {
  test::TempDir dir;
  const fs::path bag = write_stereo_bag(dir.path(), "stereo.mcap");
  DatasetOptions o;
  o.topics = {"/left/image_raw", "/right/image_raw"};
  o.max_dt = 0.005;
  const auto ds = open_dataset(bag, rectified_stereo_settings(), o);
  EXPECT_EQ(ds->kind(), "rosbag");
  EXPECT_EQ(ds->sensor(), SensorType::Stereo);
  ASSERT_EQ(ds->size(), 5u);
  EXPECT_EQ(dynamic_cast<const BagDataset&>(*ds).unpaired_first(), 1u);
  EXPECT_EQ(dynamic_cast<const BagDataset&>(*ds).unpaired_second(), 0u);
  EXPECT_DOUBLE_EQ(ds->timestamp(2), static_cast<double>(kStart + 2 * kPeriod) * 1e-9);
  const SensorFrame f = ds->load(3);
  EXPECT_EQ(cv::norm(f.gray, pattern(32, 24, 3), cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(f.right, pattern(32, 24, 103), cv::NORM_INF), 0);
  EXPECT_EQ(f.color.type(), CV_8UC3);
  ASSERT_TRUE(ds->rectified_stereo());
  EXPECT_DOUBLE_EQ(ds->rectified_stereo()->baseline, 0.1);
  // A tolerance below the 1 ms offset pairs nothing: an Error naming the flag.
  o.max_dt = 0.0005;
  EXPECT_NE(error_of([&] { open_dataset(bag, rectified_stereo_settings(), o); }).find("--pair-tolerance"),
            std::string::npos);
}

TEST(BagDataset, MissingTopicOneCameraAndNoTopicsListTheBagsTopics) {
  test::TempDir dir;
  const fs::path bag = write_stereo_bag(dir.path(), "stereo_db3", "mono8");
  DatasetOptions o;
  o.topics = {"/left/image_raw", "/rigth/image_raw"};
  std::string e = error_of([&] { open_dataset(bag, rectified_stereo_settings(), o); });
  EXPECT_NE(e.find("'/rigth/image_raw' is not in the bag"), std::string::npos) << e;
  EXPECT_NE(e.find("/right/image_raw (sensor_msgs/msg/Image, 5 messages)"), std::string::npos) << e;
  o.topics = {"/left/image_raw"};
  e = error_of([&] { open_dataset(bag, rectified_stereo_settings(), o); });
  EXPECT_NE(e.find("stereo needs two"), std::string::npos) << e;
  EXPECT_NE(e.find("/imu"), std::string::npos) << e;
  o.topics = {};
  e = error_of([&] { open_dataset(bag, rectified_stereo_settings(), o); });
  EXPECT_NE(e.find("--topics LEFT,RIGHT"), std::string::npos) << e;
  o.topics = {"/left/image_raw", "/imu"};
  e = error_of([&] { open_dataset(bag, rectified_stereo_settings(), o); });
  EXPECT_NE(e.find("not images"), std::string::npos) << e;
  // Stereo topics with settings that describe no camera pair.
  o.topics = {"/left/image_raw", "/right/image_raw"};
  CameraSettings mono;
  mono.camera = pinhole_calibration(30, 30, 16, 12, 32, 24);
  e = error_of([&] { open_dataset(bag, mono, o); });
  EXPECT_NE(e.find("--camera-info-from-bag"), std::string::npos) << e;
}

TEST(BagDataset, UnknownEncodingIsAnErrorNamingTopicAndEncoding) {
  test::TempDir dir;
  const fs::path bag = write_stereo_bag(dir.path(), "yuv.mcap", "yuv422");
  DatasetOptions o;
  o.topics = {"/left/image_raw", "/right/image_raw"};
  // Found on opening, before any frame runs.
  const std::string e = error_of([&] { open_dataset(bag, rectified_stereo_settings(), o); });
  EXPECT_NE(e.find("/right/image_raw"), std::string::npos) << e;
  EXPECT_NE(e.find("'yuv422' is not supported"), std::string::npos) << e;
  EXPECT_NE(e.find("The bag has: /left/image_raw"), std::string::npos) << e;
}

TEST(BagDataset, RgbdDepthInMillimetresAndMetres) {
  test::TempDir dir;
  auto bag = open_bag_writer(dir.path() / "rgbd.db3", BagWriterOptions{});
  const auto c = bag->add_topic("/camera/color/image_raw", ros2::kImageType);
  const auto d = bag->add_topic("/camera/depth/image_rect_raw", ros2::kCompressedImageType);
  const auto d32 = bag->add_topic("/camera/depth_m", ros2::kImageType);
  for (int k = 0; k < 3; ++k) {
    const std::int64_t t = kStart + k * kPeriod;
    cv::Mat color(24, 32, CV_8UC3, cv::Scalar(10, 20, 30 + k));
    bag->write(c, t, ros2::encode(ros2::mat_to_image(color, header(t))));
    bag->write(d, t, ros2::encode(ros2::mat_to_png(cv::Mat(24, 32, CV_16UC1, cv::Scalar(1500 + k)), header(t + 3'000'000))));
    bag->write(d32, t, ros2::encode(ros2::mat_to_image(cv::Mat(24, 32, CV_32FC1, cv::Scalar(2.5f)), header(t))));
  }
  bag->close();
  CameraSettings s;
  s.camera = pinhole_calibration(30, 30, 16, 12, 32, 24);
  s.rgbd = true;
  DatasetOptions o;
  o.topics = {"/camera/color/image_raw", "/camera/depth/image_rect_raw"};
  const auto ds = open_dataset(dir.path() / "rgbd.db3", s, o);
  EXPECT_EQ(ds->sensor(), SensorType::Rgbd);
  ASSERT_EQ(ds->size(), 3u);
  const SensorFrame f = ds->load(2);
  EXPECT_FLOAT_EQ(f.depth.at<float>(5, 5), 1.502f);
  EXPECT_EQ(f.color.at<cv::Vec3b>(0, 0), cv::Vec3b(10, 20, 32));
  EXPECT_EQ(f.gray.type(), CV_8UC1);
  // Settings that do not say: the depth encoding of the second topic decides.
  CameraSettings unsaid;
  unsaid.camera = s.camera;
  o.topics = {"/camera/color/image_raw", "/camera/depth_m"};
  const auto ds32 = open_dataset(dir.path() / "rgbd.db3", unsaid, o);
  EXPECT_EQ(ds32->sensor(), SensorType::Rgbd);
  EXPECT_FLOAT_EQ(ds32->load(0).depth.at<float>(0, 0), 2.5f);
}

TEST(BagDataset, SideBySideStereoSplitsInHalves) {
  test::TempDir dir;
  auto bag = open_bag_writer(dir.path() / "zed", BagWriterOptions{});
  const auto t = bag->add_topic("/zed/zed_node/stereo/image_rect_color", ros2::kImageType);
  for (int k = 0; k < 4; ++k) {
    cv::Mat both;
    cv::hconcat(pattern(32, 24, k), pattern(32, 24, 50 + k), both);
    cv::Mat color;
    cv::cvtColor(both, color, cv::COLOR_GRAY2BGR);
    bag->write(t, kStart + k * kPeriod, ros2::encode(ros2::mat_to_image(color, header(kStart + k * kPeriod))));
  }
  bag->close();
  DatasetOptions o;
  o.topics = {"/zed/zed_node/stereo/image_rect_color"};
  o.side_by_side = true;
  const auto ds = open_dataset(dir.path() / "zed", rectified_stereo_settings(), o);
  ASSERT_EQ(ds->size(), 4u);
  const SensorFrame f = ds->load(1);
  EXPECT_EQ(cv::norm(f.gray, pattern(32, 24, 1), cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(f.right, pattern(32, 24, 51), cv::NORM_INF), 0);
  EXPECT_EQ(f.color.size(), cv::Size(32, 24));
}

TEST(BagDataset, CalibrationFromCameraInfo) {
  test::TempDir dir;
  auto bag = open_bag_writer(dir.path() / "ci.mcap", BagWriterOptions{});
  const auto l = bag->add_topic("/stereo/left/camera_info", ros2::kCameraInfoType);
  const auto r = bag->add_topic("/stereo/right/camera_info", ros2::kCameraInfoType);
  ros2::CameraInfo info;
  info.width = 640;
  info.height = 480;
  info.distortion_model = "plumb_bob";
  info.d = {0.1, -0.05, 0, 0, 0};
  info.k = {500, 0, 320, 0, 501, 240, 0, 0, 1};
  info.r = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.p = {500, 0, 320, 0, 0, 500, 240, 0, 0, 0, 1, 0};
  bag->write(l, kStart, ros2::encode(info));
  info.p[3] = -500 * 0.12;
  bag->write(r, kStart, ros2::encode(info));
  bag->close();
  const auto reader = open_bag(dir.path() / "ci.mcap");
  CameraSettings s;
  apply_bag_camera_info(s, *reader, {"/stereo/left/image_raw", "/stereo/right/image_raw"});
  EXPECT_EQ(s.camera.fx, 500);
  EXPECT_EQ(s.camera.fy, 501);
  EXPECT_EQ(s.camera.width, 640);
  ASSERT_EQ(s.camera.distortion.size(), 5u);
  ASSERT_TRUE(s.stereo);
  EXPECT_NEAR(s.stereo->baseline, 0.12, 1e-12);
  EXPECT_NEAR(s.stereo->T_c1_c2.translation().x(), 0.12, 1e-12);
  EXPECT_FALSE(s.stereo->rectified);
  EXPECT_NEAR(s.bf, 60, 1e-9);
  const std::string e = error_of([&] { apply_bag_camera_info(s, *reader, {"/cam/image_raw"}); });
  EXPECT_NE(e.find("/cam/camera_info"), std::string::npos) << e;
  EXPECT_NE(e.find("/stereo/left/camera_info"), std::string::npos) << e;
}

TEST(BagTrajectory, OdometryPoseStampedAndTfFramePair) {
  test::TempDir dir;
  auto bag = open_bag_writer(dir.path() / "poses.mcap", BagWriterOptions{});
  const auto odom_t = bag->add_topic("/odom", ros2::kOdometryType);
  const auto pose_t = bag->add_topic("/pose", ros2::kPoseStampedType);
  const auto tf_t = bag->add_topic("/tf", ros2::kTfMessageType);
  for (int k = 0; k < 5; ++k) {
    const std::int64_t t = kStart + k * kPeriod;
    ros2::Odometry odom;
    odom.header = header(t);
    odom.pose.position = {0.1 * k, 0, 0};
    bag->write(odom_t, t, ros2::encode(odom));
    ros2::PoseStamped pose;
    pose.header = header(t);
    pose.pose.position = {0, 0.2 * k, 0};
    pose.pose.orientation = {0, 0, std::sin(0.05 * k), std::cos(0.05 * k)};
    bag->write(pose_t, t, ros2::encode(pose));
    ros2::TfMessage tf;
    tf.transforms.resize(2);
    tf.transforms[0].header = header(t);
    tf.transforms[0].header.frame_id = "odom";
    tf.transforms[0].child_frame_id = "base_link";
    tf.transforms[0].transform.position = {0, 0, 0.3 * k};
    tf.transforms[1].header = header(t);
    tf.transforms[1].header.frame_id = "map";
    tf.transforms[1].child_frame_id = "odom";
    bag->write(tf_t, t, ros2::encode(tf));
  }
  bag->close();
  const auto reader = open_bag(dir.path() / "poses.mcap");
  const Trajectory odom = read_bag_trajectory(*reader, {"/odom", {}});
  ASSERT_EQ(odom.size(), 5u);
  EXPECT_DOUBLE_EQ(odom[4].T_world_cam.translation().x(), 0.4);
  EXPECT_DOUBLE_EQ(odom[1].timestamp, static_cast<double>(kStart + kPeriod) * 1e-9);
  const Trajectory pose = read_bag_trajectory(*reader, {"/pose", {}});
  EXPECT_NEAR(Eigen::AngleAxisd(pose[4].T_world_cam.linear()).angle(), 0.4, 1e-12);
  const Trajectory tf = read_bag_trajectory(*reader, {"/tf", std::pair<std::string, std::string>{"odom", "base_link"}});
  ASSERT_EQ(tf.size(), 5u);
  EXPECT_DOUBLE_EQ(tf[3].T_world_cam.translation().z(), 0.9);
  std::string e = error_of([&] { read_bag_trajectory(*reader, {"/tf", {}}); });
  EXPECT_NE(e.find("map,odom"), std::string::npos) << e;
  e = error_of([&] { read_bag_trajectory(*reader, {"/gps", {}}); });
  EXPECT_NE(e.find("/odom (nav_msgs/msg/Odometry)"), std::string::npos) << e;
}

}  // namespace
}  // namespace stillslam
