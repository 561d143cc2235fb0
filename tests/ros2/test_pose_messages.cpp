#include <gtest/gtest.h>

#include "pose_messages.h"

namespace stillslam::ros2 {
namespace {

Eigen::Isometry3d some_pose() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.5, -1.25, 2);
  return T;
}

TEST(PoseMessages, PoseStampedCarriesTheCameraInTheMapFrame) {
  const std::string map = "map";
  const auto m = pose_stamped(some_pose(), 5000000001LL, map);
  EXPECT_STREQ(m.header.frame_id, "map");
  EXPECT_EQ(m.header.stamp.sec, 5);
  EXPECT_EQ(m.header.stamp.nanosec, 1u);
  EXPECT_DOUBLE_EQ(m.pose.position.y, -1.25);
  const auto& q = m.pose.orientation;
  EXPECT_NEAR(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w, 1.0, 1e-12);
  EXPECT_TRUE(pose_from_message(m.pose).isApprox(some_pose(), 1e-12));
}

TEST(PoseMessages, TfIsMapToCamera) {
  const std::string map = "map", camera = "camera";
  const TfMessage tf(some_pose(), 7, map, camera);
  const auto& m = tf.message();
  ASSERT_EQ(m.transforms._length, 1u);
  const auto& t = m.transforms._buffer[0];
  EXPECT_STREQ(t.header.frame_id, "map");
  EXPECT_STREQ(t.child_frame_id, "camera");
  EXPECT_EQ(t.header.stamp.nanosec, 7u);
  EXPECT_DOUBLE_EQ(t.transform.translation.z, 2.0);
  const auto p = pose_message(some_pose());
  EXPECT_DOUBLE_EQ(t.transform.rotation.w, p.orientation.w);
}

TEST(PoseMessages, PathKeepsTheNewestPoses) {
  PathMessage path("map", 3);
  for (int i = 0; i < 5; ++i) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation().x() = i;
    path.add(T, i);
  }
  const auto& m = path.message(99);
  EXPECT_STREQ(m.header.frame_id, "map");
  EXPECT_EQ(m.header.stamp.nanosec, 99u);
  ASSERT_EQ(m.poses._length, 3u);
  EXPECT_DOUBLE_EQ(m.poses._buffer[0].pose.position.x, 2.0);
  EXPECT_DOUBLE_EQ(m.poses._buffer[2].pose.position.x, 4.0);
  EXPECT_STREQ(m.poses._buffer[2].header.frame_id, "map");
  path.clear();
  EXPECT_EQ(path.message(100).poses._length, 0u);
}

}  // namespace
}  // namespace stillslam::ros2
