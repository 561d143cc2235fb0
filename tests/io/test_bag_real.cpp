// The real ROS 2 bags of ../shared (rosbags / evo test data): every message
// is read, the per-topic counts equal metadata.yaml / the MCAP summary, and
// the TF and odometry messages decode to unit quaternions with monotonic stamps.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "stillslam/io/bag_metadata.h"
#include "stillslam/io/bag_reader.h"
#include "stillslam/io/bag_trajectory.h"
#include "stillslam/io/mcap_reader.h"
#include "stillslam/io/ros2_message_codec.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;
const fs::path kTrajectories = fs::path(STILLSLAM_SHARED_DIR) / "data" / "trajectories";

double norm(const ros2::Pose& p) {
  const auto& q = p.orientation;
  return std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
}

// Decodes every TF / odometry message; returns how many poses it checked.
std::size_t check_poses(const BagReader& bag) {
  std::size_t poses = 0;
  std::map<std::string, std::int64_t> last_stamp;  // per topic + child frame
  for (std::size_t i = 0; i < bag.messages().size(); ++i) {
    const BagTopic& topic = bag.topics()[bag.messages()[i].topic];
    const auto bytes = bag.read(i);
    const auto check = [&](const std::string& key, const ros2::Header& h, const ros2::Pose& pose) {
      EXPECT_NEAR(norm(pose), 1.0, 1e-6) << topic.name << " message " << i;
      if (topic.name != "/tf_static") {
        const auto it = last_stamp.find(key);
        if (it != last_stamp.end()) {
          EXPECT_GE(h.stamp_ns(), it->second) << key << " message " << i;
        }
        last_stamp[key] = h.stamp_ns();
      }
      ++poses;
    };
    if (topic.type == ros2::kTfMessageType) {
      for (const auto& t : ros2::decode_tf_message(bytes, topic.name).transforms) {
        check(topic.name + " " + t.header.frame_id + "->" + t.child_frame_id, t.header, t.transform);
      }
    } else if (topic.type == ros2::kOdometryType) {
      const ros2::Odometry odom = ros2::decode_odometry(bytes, topic.name);
      check(topic.name, odom.header, odom.pose);
    }
  }
  return poses;
}

TEST(BagReal, Db3CountsMatchMetadataAndPosesDecode) {
  const fs::path bag_dir = kTrajectories / "tf_example";
  if (!fs::exists(bag_dir)) GTEST_SKIP() << "shared data not found at " << bag_dir << " (../shared next to the repo)";
  const BagMetadata metadata = read_bag_metadata(bag_dir / "metadata.yaml");
  const auto bag = open_bag(bag_dir);
  EXPECT_EQ(bag->storage(), "sqlite3");
  EXPECT_TRUE(bag->damage().empty());
  ASSERT_EQ(metadata.topics.size(), 2u);
  EXPECT_EQ(bag->messages().size(), 518u);
  for (const BagTopic& expected : metadata.topics) {
    const auto t = bag->find_topic(expected.name);
    ASSERT_TRUE(t) << expected.name;
    EXPECT_EQ(bag->topics()[*t].message_count, expected.message_count) << expected.name;
    EXPECT_EQ(bag->topics()[*t].type, expected.type);
  }
  EXPECT_GE(check_poses(*bag), 518u);
}

TEST(BagReal, McapCountsMatchSummaryAndPosesDecode) {
  const fs::path file = kTrajectories / "nav2_turtlebot.mcap";
  if (!fs::exists(file)) GTEST_SKIP() << "shared data not found at " << file << " (../shared next to the repo)";
  const McapReader bag(file);
  EXPECT_TRUE(bag.damage().empty());
  ASSERT_TRUE(bag.summary_counts());
  std::size_t total = 0;
  for (const auto& [name, n] : *bag.summary_counts()) {
    const auto t = bag.find_topic(name);
    ASSERT_TRUE(t) << name;
    EXPECT_EQ(bag.topics()[*t].message_count, n) << name;
    total += n;
  }
  EXPECT_EQ(bag.messages().size(), total);
  EXPECT_GT(total, 0u);
  EXPECT_GT(check_poses(bag), 0u);
  // The odom -> base_link TF and the odometry topic carry the same poses.
  const Trajectory odom = read_bag_trajectory(bag, {"/odom", {}});
  const Trajectory tf = read_bag_trajectory(bag, {"/tf", std::pair<std::string, std::string>{"odom", "base_link"}});
  ASSERT_EQ(odom.size(), 2639u);
  ASSERT_EQ(tf.size(), odom.size());
  for (std::size_t i = 0; i < odom.size(); i += 100) {
    EXPECT_EQ(tf[i].timestamp, odom[i].timestamp);
    EXPECT_LT((tf[i].T_world_cam.translation() - odom[i].T_world_cam.translation()).norm(), 1e-9);
  }
  EXPECT_EQ(read_bag_trajectory(bag, {"/amcl_pose", {}}).size(), 135u);
}

}  // namespace
}  // namespace stillslam
