// Two processes on loopback: `stillslam ros2-replay --lockstep` publishes the
// EuRoC clip, `stillslam ros2` tracks it; this test subscribes to the node's
// outputs (and the replay's images) with the same generated types and
// compares the published poses with an offline `stillslam run` of the clip.
// Both runs are --deterministic --no-segmentation without a vocabulary, so
// they see the same frames in the same order; lockstep means no frame is
// dropped, however slow the machine. Every wait has a timeout.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include <nlohmann/json.hpp>

#include "common/child_process.h"
#include "common/run_stillslam.h"
#include "dds.h"
#include "geometry_msgs/msg/PoseStamped.h"
#include "nav_msgs/msg/Path.h"
#include "pose_messages.h"
#include "ros_time.h"
#include "sensor_msgs/msg/CameraInfo.h"
#include "sensor_msgs/msg/Image.h"
#include "std_msgs/msg/String.h"
#include "stillslam/io/trajectory.h"
#include "tf2_msgs/msg/TFMessage.h"

namespace stillslam::ros2 {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const fs::path kClip = fs::path(STILLSLAM_SHARED_DIR) / "data" / "euroc_V1_01_micro";
const std::string kConfig = std::string(STILLSLAM_SOURCE_DIR) + "/config/euroc.yaml";

struct Received {
  std::map<std::int64_t, Eigen::Isometry3d> poses;  // by header stamp
  std::size_t states = 0, states_ok = 0, tf = 0, images = 0, camera_infos = 0;
  std::size_t last_path_length = 0;
  std::string bad_layout;  // the first message that did not look as expected
};

void check(bool ok, const std::string& what, Received& r) {
  if (!ok && r.bad_layout.empty()) r.bad_layout = what;
}

TEST(Ros2Live, NodePosesMatchTheOfflineRunOverLoopback) {
  REQUIRE_STILLSLAM_BINARY();
  if (!fs::exists(kClip)) GTEST_SKIP() << kClip << " is absent (../shared is not on this machine)";
  const fs::path tmp = fs::temp_directory_path() / ("stillslam_ros2_live_" + std::to_string(::getpid()));
  fs::remove_all(tmp);
  // Each test its own range of domains (tests run side by side), never ROS 2's 0.
  const int domain = 1 + static_cast<int>(::getpid() % 60);
  const std::string d = std::to_string(domain);

  DdsNetworkOptions network;
  network.domain = domain;
  const DdsParticipant participant(network);
  const DdsReader<geometry_msgs_msg_dds__PoseStamped_> pose(participant, geometry_msgs_msg_dds__PoseStamped__desc, "stillslam/pose");
  const DdsReader<nav_msgs_msg_dds__Path_> path(participant, nav_msgs_msg_dds__Path__desc, "stillslam/path");
  const DdsReader<tf2_msgs_msg_dds__TFMessage_> tf(participant, tf2_msgs_msg_dds__TFMessage__desc, "tf");
  const DdsReader<std_msgs_msg_dds__String_> state(participant, std_msgs_msg_dds__String__desc, "stillslam/tracking_state");
  const DdsReader<sensor_msgs_msg_dds__Image_> left(participant, sensor_msgs_msg_dds__Image__desc, "camera/left/image_raw");
  const DdsReader<sensor_msgs_msg_dds__CameraInfo_> info(participant, sensor_msgs_msg_dds__CameraInfo__desc, "camera/right/camera_info");

  test::ChildProcess node({"ros2", "--config", kConfig, "--output", (tmp / "node").string(), "--domain", d,
                           "--no-segmentation", "--deterministic", "--vocabulary", "none", "--rectified-input"});
  ASSERT_TRUE(pose.wait_matched(1, 30s) && state.wait_matched(1, 30s)) << "the node did not come up";
  test::ChildProcess replay({"ros2-replay", kClip.string(), "--config", kConfig, "--domain", d, "--lockstep",
                             "--wait-subscriber", "30", "--lockstep-timeout", "60"});

  Received r;
  auto take_all = [&] {
    pose.take([&](const geometry_msgs_msg_dds__PoseStamped_& m) {
      check(std::string(m.header.frame_id) == "map", "pose frame_id", r);
      r.poses[stamp_nanoseconds(m.header.stamp)] = pose_from_message(m.pose);
    });
    tf.take([&](const tf2_msgs_msg_dds__TFMessage_& m) {
      ++r.tf;
      check(m.transforms._length == 1 && std::string(m.transforms._buffer[0].header.frame_id) == "map" &&
                std::string(m.transforms._buffer[0].child_frame_id) == "camera",
            "tf layout", r);
    });
    path.take([&](const nav_msgs_msg_dds__Path_& m) {
      check(std::string(m.header.frame_id) == "map", "path frame_id", r);
      r.last_path_length = m.poses._length;
    });
    state.take([&](const std_msgs_msg_dds__String_& m) {
      ++r.states;
      r.states_ok += std::string(m.data) == "ok" ? 1 : 0;
    });
    left.take([&](const sensor_msgs_msg_dds__Image_& m) {
      ++r.images;
      check(std::string(m.encoding) == "mono8" && m.width == 752 && m.height == 480 && m.step == 752 &&
                m.data._length == 752u * 480u && std::string(m.header.frame_id) == "camera",
            "image layout", r);
    });
    info.take([&](const sensor_msgs_msg_dds__CameraInfo_& m) {
      ++r.camera_infos;
      check(m.width == 752 && m.height == 480 && m.p[3] < -0.1 * m.p[0] && m.d._length == 5, "camera info layout", r);
    });
  };
  const auto deadline = std::chrono::steady_clock::now() + 120s;
  while (!replay.exited() && std::chrono::steady_clock::now() < deadline) {
    take_all();
    std::this_thread::sleep_for(5ms);
  }
  ASSERT_TRUE(replay.exited()) << "ros2-replay did not finish within 120 s";
  ASSERT_EQ(replay.wait(), 0) << replay.output();
  for (int i = 0; i < 200 && r.states < 95; ++i) {  // the last messages may still be on their way
    take_all();
    std::this_thread::sleep_for(10ms);
  }
  node.send(SIGTERM);
  for (int i = 0; i < 3000 && !node.exited(); ++i) std::this_thread::sleep_for(10ms);
  ASSERT_TRUE(node.exited()) << "the node did not exit within 30 s of SIGTERM";
  ASSERT_EQ(node.wait(), 0) << test::describe_status(node.wait()) << "\n" << node.output();

  EXPECT_EQ(r.bad_layout, "");
  EXPECT_EQ(r.states, 95u);
  EXPECT_EQ(r.images, 95u);
  EXPECT_EQ(r.camera_infos, 95u);
  EXPECT_EQ(r.tf, r.poses.size());
  EXPECT_EQ(r.last_path_length, r.poses.size());

  std::ifstream stats_file(tmp / "node" / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(stats_file);
  EXPECT_EQ(stats["ros2"]["received"], nlohmann::json({95, 95}));
  EXPECT_EQ(stats["ros2"]["unpaired"], nlohmann::json({0, 0}));
  EXPECT_EQ(stats["ros2"]["dropped_stale"], 0);
  EXPECT_EQ(stats["ros2"]["camera_info_messages"], 95);  // the default: camera/left/camera_info
  EXPECT_NE(node.output().find("CameraInfo on rt/camera/left/camera_info agrees with the settings"), std::string::npos);
  EXPECT_EQ(stats["end"]["reason"], "interrupted");
  EXPECT_EQ(stats["end"]["signal"], "SIGTERM");
  EXPECT_TRUE(fs::exists(tmp / "node" / "trajectory.txt"));

  const test::CommandRun offline =
      test::run_stillslam("run --config " + kConfig + " --input " + kClip.string() + " --output " + (tmp / "offline").string() +
                              " --no-segmentation --deterministic --vocabulary none",
                          true);
  ASSERT_EQ(offline.status, 0) << offline.out;
  const Trajectory expected = read_trajectory(tmp / "offline" / "trajectory_live.txt");
  ASSERT_GT(expected.size(), 80u);
  EXPECT_EQ(r.poses.size(), expected.size());
  double worst = 0;
  std::size_t matched = 0;
  for (const StampedPose& e : expected) {
    const std::int64_t ns = nanoseconds_from_seconds(e.timestamp);
    auto it = r.poses.lower_bound(ns - 1000000);  // the file keeps ~0.1 us of the stamp
    if (it == r.poses.end() || it->first > ns + 1000000) continue;
    ++matched;
    worst = std::max(worst, (it->second.translation() - e.T_world_cam.translation()).norm());
  }
  EXPECT_EQ(matched, expected.size());
  EXPECT_LT(worst, 0.01);
  std::cout << "ros2 live: " << r.poses.size() << " poses, worst position difference to the offline run " << worst
            << " m\n";
  fs::remove_all(tmp);
}

// RGB-D over loopback (colour bgr8, depth 32FC1 in metres) on a small
// generated sequence: needs no ../shared.
TEST(Ros2Live, RgbdSequenceMatchesTheOfflineRun) {
  REQUIRE_STILLSLAM_BINARY();
  const fs::path tmp = fs::temp_directory_path() / ("stillslam_ros2_rgbd_" + std::to_string(::getpid()));
  fs::remove_all(tmp);
  const std::string seq = (tmp / "seq").string(), settings = (tmp / "seq" / "settings.yaml").string();
  const test::CommandRun sim = test::run_stillslam(
      "simulate --out " + seq + " --frames 12 --width 320 --height 240 --supersampling 1 --people 1", true);
  ASSERT_EQ(sim.status, 0) << sim.out;
  const int domain = 101 + static_cast<int>(::getpid() % 40);
  const std::string d = std::to_string(domain);
  DdsNetworkOptions network;
  network.domain = domain;
  const DdsParticipant participant(network);
  const DdsReader<geometry_msgs_msg_dds__PoseStamped_> pose(participant, geometry_msgs_msg_dds__PoseStamped__desc, "stillslam/pose");
  const DdsReader<sensor_msgs_msg_dds__Image_> depth(participant, sensor_msgs_msg_dds__Image__desc, "camera/depth/image_raw");
  test::ChildProcess node({"ros2", "--config", settings, "--output", (tmp / "node").string(), "--domain", d,
                           "--no-segmentation", "--deterministic", "--vocabulary", "none", "--max-frames", "12"});
  ASSERT_TRUE(pose.wait_matched(1, 30s)) << "the node did not come up";
  test::ChildProcess replay({"ros2-replay", seq, "--config", settings, "--domain", d, "--lockstep",
                             "--wait-subscriber", "30", "--lockstep-timeout", "60"});
  std::map<std::int64_t, Eigen::Isometry3d> poses;
  std::size_t depths = 0;
  std::string bad;
  const auto deadline = std::chrono::steady_clock::now() + 120s;
  while (!(replay.exited() && node.exited()) && std::chrono::steady_clock::now() < deadline) {
    pose.take([&](const geometry_msgs_msg_dds__PoseStamped_& m) {
      poses[stamp_nanoseconds(m.header.stamp)] = pose_from_message(m.pose);
    });
    depth.take([&](const sensor_msgs_msg_dds__Image_& m) {
      ++depths;
      if (std::string(m.encoding) != "32FC1" || m.width != 320 || m.height != 240 || m.step != 4 * 320) bad = "depth layout";
    });
    std::this_thread::sleep_for(5ms);
  }
  pose.take([&](const geometry_msgs_msg_dds__PoseStamped_& m) {
    poses[stamp_nanoseconds(m.header.stamp)] = pose_from_message(m.pose);
  });
  ASSERT_TRUE(replay.exited() && node.exited()) << "did not finish within 120 s";
  ASSERT_EQ(replay.wait(), 0) << replay.output();
  ASSERT_EQ(node.wait(), 0) << node.output();
  EXPECT_EQ(bad, "");
  EXPECT_EQ(depths, 12u);
  const test::CommandRun offline = test::run_stillslam("run --config " + settings + " --input " + seq + " --output " +
                                                           (tmp / "offline").string() +
                                                           " --no-segmentation --deterministic --vocabulary none",
                                                       true);
  ASSERT_EQ(offline.status, 0) << offline.out;
  const Trajectory expected = read_trajectory(tmp / "offline" / "trajectory_live.txt");
  ASSERT_GE(expected.size(), 10u);
  ASSERT_EQ(poses.size(), expected.size());
  double worst = 0;
  auto it = poses.begin();
  for (const StampedPose& e : expected) {
    EXPECT_NEAR(static_cast<double>(it->first) * 1e-9, e.timestamp, 1e-6);
    worst = std::max(worst, (it->second.translation() - e.T_world_cam.translation()).norm());
    ++it;
  }
  EXPECT_LT(worst, 0.01);
  fs::remove_all(tmp);
}

// With segmentation on, the node also sends the dynamic mask of every frame
// (the clip has no people: all zeros, but the layout is what a ROS 2 viewer needs).
TEST(Ros2Live, DynamicMaskIsAMono8ImageOfTheFrame) {
  REQUIRE_STILLSLAM_BINARY();
  if (!fs::exists(kClip)) GTEST_SKIP() << kClip << " is absent (../shared is not on this machine)";
  const fs::path tmp = fs::temp_directory_path() / ("stillslam_ros2_mask_" + std::to_string(::getpid()));
  fs::remove_all(tmp);
  const int domain = 61 + static_cast<int>(::getpid() % 40);
  const std::string d = std::to_string(domain);
  DdsNetworkOptions network;
  network.domain = domain;
  const DdsParticipant participant(network);
  const DdsReader<sensor_msgs_msg_dds__Image_> mask(participant, sensor_msgs_msg_dds__Image__desc, "stillslam/dynamic_mask");
  const DdsReader<std_msgs_msg_dds__String_> state(participant, std_msgs_msg_dds__String__desc, "stillslam/tracking_state");
  test::ChildProcess node({"ros2", "--config", kConfig, "--output", tmp.string(), "--domain", d, "--vocabulary",
                           "none", "--rectified-input", "--max-frames", "3"});
  ASSERT_TRUE(mask.wait_matched(1, 30s)) << "the node did not come up";
  test::ChildProcess replay({"ros2-replay", kClip.string(), "--config", kConfig, "--domain", d, "--lockstep",
                             "--max-frames", "3", "--wait-subscriber", "30", "--lockstep-timeout", "60"});
  std::size_t masks = 0, states = 0;
  std::string bad;
  const auto deadline = std::chrono::steady_clock::now() + 120s;
  while (!(replay.exited() && node.exited() && states >= 3) && std::chrono::steady_clock::now() < deadline) {
    mask.take([&](const sensor_msgs_msg_dds__Image_& m) {
      ++masks;
      bool binary = true;
      for (std::uint32_t i = 0; i < m.data._length; ++i) binary = binary && (m.data._buffer[i] == 0 || m.data._buffer[i] == 255);
      if (std::string(m.encoding) != "mono8" || m.width != 752 || m.height != 480 || m.step != 752 ||
          m.data._length != 752u * 480u || std::string(m.header.frame_id) != "camera" || !binary) {
        bad = "mask layout";
      }
    });
    states += state.take([](const std_msgs_msg_dds__String_&) {});
    std::this_thread::sleep_for(5ms);
  }
  ASSERT_TRUE(replay.exited() && node.exited()) << "did not finish within 120 s";
  EXPECT_EQ(replay.wait(), 0) << replay.output();
  EXPECT_EQ(node.wait(), 0) << node.output();  // --max-frames 3: the node ends by itself
  EXPECT_EQ(bad, "");
  EXPECT_EQ(states, 3u);
  EXPECT_EQ(masks, 3u);
  fs::remove_all(tmp);
}

}  // namespace
}  // namespace stillslam::ros2
