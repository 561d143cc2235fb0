// What keyframes and map points keep between calls: a keyframe's inverse pose
// (kept with the pose) and a point's distinctive descriptor (not recomputed
// while its observations are unchanged) must always equal a fresh computation.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <vector>

#include "../common/synthetic_camera.h"
#include "stillslam/map/frame.h"
#include "stillslam/map/keyframe.h"
#include "stillslam/map/map_point.h"

namespace stillslam {
namespace {

bool bitwise_equal(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return std::memcmp(a.matrix().data(), b.matrix().data(), sizeof(double) * 16) == 0;
}

Eigen::Isometry3d some_pose(double angle, double x) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(angle, Eigen::Vector3d(0.3, -1.0, 0.2).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, -0.7, 2.3);
  return T;
}

// A posed keyframe with one mono keypoint whose descriptor has its first `bits` bits set.
KeyFramePtr keyframe_with_descriptor(std::uint64_t id, int bits) {
  test::SceneDescriptor d{};
  for (int b = 0; b < bits; ++b) d[static_cast<std::size_t>(b / 8)] |= static_cast<std::uint8_t>(1u << (b % 8));
  std::vector<cv::KeyPoint> kps{cv::KeyPoint(100.f, 120.f, 31.f, 0.f, 1.f, 0)};
  Frame frame(id, 0.1 * static_cast<double>(id), test::synthetic_camera_setup(), kps, kps, test::descriptor_row(d),
              {-1.f}, {-1.f});
  frame.set_pose(some_pose(0.1 * static_cast<double>(id), 0.2 * static_cast<double>(id)));
  return std::make_shared<KeyFrame>(id, frame);
}

int set_bits(const std::uint8_t* d) {
  int n = 0;
  for (int i = 0; i < 32; ++i) n += __builtin_popcount(d[i]);
  return n;
}

TEST(KeyFrameInversePose, KeptEqualToTheInverseOfThePose) {
  const KeyFramePtr kf = keyframe_with_descriptor(3, 0);
  EXPECT_TRUE(bitwise_equal(kf->T_world_cam(), kf->T_cam_world().inverse()));
  const Eigen::Isometry3d T = some_pose(1.1, -4.5);
  kf->set_pose(T);
  EXPECT_TRUE(bitwise_equal(kf->T_cam_world(), T));
  EXPECT_TRUE(bitwise_equal(kf->T_world_cam(), T.inverse()));
  const Eigen::Vector3d centre = T.inverse().translation();
  EXPECT_EQ(std::memcmp(kf->camera_center().data(), centre.data(), sizeof(double) * 3), 0);
  // The centre moved with the pose (it is not the first pose's).
  EXPECT_GT((kf->camera_center() - some_pose(0.3, 0.6).inverse().translation()).norm(), 1.0);
}

TEST(MapPointDescriptor, RecomputedWhenObservationsChangeOnly) {
  // Descriptors with the first 0, 8, 32 and 12 bits set: distances a-b 8, a-c 32, b-c 24, a-d 12, b-d 4, c-d 20.
  const KeyFramePtr a = keyframe_with_descriptor(0, 0), b = keyframe_with_descriptor(1, 8);
  const KeyFramePtr c = keyframe_with_descriptor(2, 32), d = keyframe_with_descriptor(3, 12);
  MapPoint mp(0, Eigen::Vector3d(0, 0, 3), a.get());
  mp.add_observation(a.get(), 0);
  mp.add_observation(b.get(), 0);
  mp.add_observation(c.get(), 0);
  mp.compute_distinctive_descriptor();
  // Medians (second smallest of three): a 8, b 8, c 24; the tie goes to the first keyframe.
  EXPECT_EQ(set_bits(mp.descriptor()), 0);
  mp.compute_distinctive_descriptor();
  EXPECT_EQ(set_bits(mp.descriptor()), 0);

  // With d (second smallest of four): a 8, b 4, c 20, d 4: b.
  mp.add_observation(d.get(), 0);
  mp.compute_distinctive_descriptor();
  EXPECT_EQ(set_bits(mp.descriptor()), 8);
  mp.add_observation(d.get(), 0);  // already there: no change
  mp.compute_distinctive_descriptor();
  EXPECT_EQ(set_bits(mp.descriptor()), 8);

  // Without d again: a.
  mp.erase_observation(d.get());
  mp.compute_distinctive_descriptor();
  EXPECT_EQ(set_bits(mp.descriptor()), 0);

  // An overwritten descriptor is recomputed, not kept.
  test::SceneDescriptor ones;
  ones.fill(0xFF);
  mp.set_descriptor(ones.data());
  EXPECT_EQ(set_bits(mp.descriptor()), 256);
  mp.compute_distinctive_descriptor();
  EXPECT_EQ(set_bits(mp.descriptor()), 0);

  // The same as a point built with these observations from scratch, in any order.
  mp.add_observation(d.get(), 0);
  MapPoint fresh(1, Eigen::Vector3d(0, 0, 3), d.get());
  for (const KeyFramePtr& kf : {d, c, b, a}) fresh.add_observation(kf.get(), 0);
  fresh.compute_distinctive_descriptor();
  mp.compute_distinctive_descriptor();
  EXPECT_EQ(std::memcmp(mp.descriptor(), fresh.descriptor(), 32), 0);
  EXPECT_EQ(set_bits(mp.descriptor()), 8);
}

}  // namespace
}  // namespace stillslam
