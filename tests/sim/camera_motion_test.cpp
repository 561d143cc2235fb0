// Camera paths: replayed ground truth and the generated paths' geometry.
#include <gtest/gtest.h>

#include <filesystem>

#include "stillslam/io/trajectory.h"
#include "stillslam/sim/camera_motion.h"
#include "stillslam/sim/scene_layout.h"

namespace stillslam::sim {
namespace {
namespace fs = std::filesystem;

const fs::path kData = fs::path(STILLSLAM_SOURCE_DIR) / "data";

TEST(CameraMotion, WalkingXyzReplaysTheTumGroundTruth) {
  const CameraMotion m = CameraMotion::create("walking_xyz", kData, 0);
  const Trajectory gt = read_trajectory(kData / "sim" / "tum_fr3_walking_xyz_groundtruth.txt");
  ASSERT_EQ(gt.size(), 2884u);
  EXPECT_TRUE(m.replayed());
  EXPECT_EQ(m.start_ns(), 1341846313637800000LL);
  EXPECT_NEAR(m.duration(), gt.back().timestamp - gt.front().timestamp, 1e-9);
  // At a ground-truth stamp the pose is that pose; between two it interpolates.
  const double dt = gt[100].timestamp - gt[0].timestamp;
  EXPECT_TRUE(m.pose_at(dt).isApprox(gt[100].T_world_cam, 1e-9));
  const double mid = 0.5 * (gt[100].timestamp + gt[101].timestamp) - gt[0].timestamp;
  const Eigen::Vector3d expected =
      0.5 * (gt[100].T_world_cam.translation() + gt[101].T_world_cam.translation());
  EXPECT_LT((m.pose_at(mid).translation() - expected).norm(), 1e-6);  // stamps ~1.3e9 s: 1e-7 s resolution
}

TEST(CameraMotion, HalfSphereLooksAtItsCentreFromOneMetre) {
  const CameraMotion m = CameraMotion::create("halfsphere", kData, 4);
  const Eigen::Vector3d centre = SceneLayout::desk_centre() + Eigen::Vector3d(0, 0, 0.1);
  for (double t : {0.0, 3.3, 7.1, 12.0}) {
    const Eigen::Isometry3d T = m.pose_at(t);
    const Eigen::Vector3d c_cam = T.inverse() * centre;
    EXPECT_NEAR(c_cam.norm(), 1.0, 1e-9);
    EXPECT_NEAR(c_cam.x(), 0, 1e-9);  // on the optical axis
    EXPECT_NEAR(c_cam.y(), 0, 1e-9);
    EXPECT_GT(T.translation().z(), centre.z());  // upper half sphere
  }
}

TEST(CameraMotion, RpyRotatesAboutAFixedPointAndStaticBarelyMoves) {
  const CameraMotion rpy = CameraMotion::create("rpy", kData, 1);
  const CameraMotion still = CameraMotion::create("static", kData, 1);
  double max_angle = 0, max_still_move = 0;
  for (double t = 0; t < 12; t += 0.25) {
    EXPECT_LT(rpy.pose_at(t).translation().norm(), 1e-12);
    max_angle = std::max(max_angle, Eigen::AngleAxisd(rpy.pose_at(t).linear() *
                                                      rpy.pose_at(0).linear().transpose())
                                        .angle());
    max_still_move = std::max(max_still_move, (still.pose_at(t).translation() - still.pose_at(0).translation()).norm());
  }
  EXPECT_GT(max_angle, 0.3);
  EXPECT_LT(max_still_move, 0.01);
}

TEST(CameraMotion, UnknownTrajectoryNamesTheChoices) {
  try {
    CameraMotion::create("spiral", kData, 0);
    FAIL() << "expected an error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("halfsphere"), std::string::npos);
  }
}

}  // namespace
}  // namespace stillslam::sim
