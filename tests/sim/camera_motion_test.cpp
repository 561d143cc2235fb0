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

TEST(CameraMotion, HalfSphereMovesOnAHalfSphereFacingTheDesk) {
  // TUM fr3/walking_halfsphere: moved over a half sphere of ~1 m diameter,
  // facing the desk and the people, at ~0.2 m/s.
  const CameraMotion m = CameraMotion::create("halfsphere", kData, 4);
  const Eigen::Vector3d centre(0, 0.35, 0);
  double path = 0, max_angle = 0;
  Eigen::Isometry3d prev = m.pose_at(0);
  for (double t = 0.1; t <= 16.0 + 1e-9; t += 0.1) {
    const Eigen::Isometry3d T = m.pose_at(t);
    EXPECT_NEAR((T.translation() - centre).norm(), 0.5, 1e-9);
    EXPECT_LE(T.translation().y(), centre.y());  // the half away from the desk
    const Eigen::Vector3d desk = T.inverse() * SceneLayout::desk_centre();
    EXPECT_GT(desk.z(), 1.2);  // in front, 1.2 m or more away
    EXPECT_LT(std::abs(desk.x()) / desk.z(), 0.6);  // inside the view
    EXPECT_LT(std::abs(desk.y()) / desk.z(), 0.45);
    path += (T.translation() - prev.translation()).norm();
    max_angle = std::max(max_angle, Eigen::AngleAxisd(T.linear().transpose() * m.pose_at(0).linear()).angle());
    prev = T;
  }
  EXPECT_GT(path / 16.0, 0.12);  // m/s over one turn
  EXPECT_LT(path / 16.0, 0.35);
  EXPECT_GT(max_angle, 0.3);  // it turns, too (rad)
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

TEST(CameraMotion, LoopTurnsOnceAroundTheRoomAndComesBackToItsStartPose) {
  const CameraMotion m = CameraMotion::create("loop", kData, 3);
  const double T = CameraMotion::kLoopPeriod;
  // Periodic: the start pose again after one turn (and a few seconds later, the same poses as then).
  EXPECT_TRUE(m.pose_at(T).isApprox(m.pose_at(0), 1e-9));
  EXPECT_TRUE(m.pose_at(T + 2.5).isApprox(m.pose_at(2.5), 1e-9));
  // Starts in front of the desk looking at it (along +y), and its heading turns through a whole circle.
  const Eigen::Vector3d axis0 = m.pose_at(0).linear().col(2);
  EXPECT_GT(Eigen::Vector3d(axis0.x(), axis0.y(), 0).normalized().y(), 0.999);
  EXPECT_LT(m.pose_at(0).translation().y(), SceneLayout::desk_centre().y() - 0.4);
  double turned = 0, min_wall = 1e9, max_step = 0, max_turn = 0;
  double previous = std::atan2(m.pose_at(0).linear()(0, 2), m.pose_at(0).linear()(1, 2));
  for (double t = 0.1; t <= T + 1e-9; t += 0.1) {
    const Eigen::Isometry3d P = m.pose_at(t);
    const Eigen::Isometry3d Q = m.pose_at(t - 0.1);
    const double heading = std::atan2(P.linear()(0, 2), P.linear()(1, 2));
    turned += std::remainder(heading - previous, 6.283185307179586);
    previous = heading;
    const Eigen::Vector3d p = P.translation();
    min_wall = std::min({min_wall, p.x() - SceneLayout::kMinX, SceneLayout::kMaxX - p.x(),
                         p.y() - SceneLayout::kMinY, SceneLayout::kMaxY - p.y()});
    max_step = std::max(max_step, (p - Q.translation()).norm());
    max_turn = std::max(max_turn, Eigen::AngleAxisd(P.linear() * Q.linear().transpose()).angle());
    EXPECT_LT(std::abs(P.linear().col(0).z()), 1e-9) << "no roll";
    EXPECT_LT(P.linear().col(2).z(), 0) << "looks slightly down";
  }
  EXPECT_NEAR(std::abs(turned), 6.283185307179586, 1e-6);
  EXPECT_GT(min_wall, 1.5);       // always 1.5 m or more from every wall
  EXPECT_LT(max_step, 0.03);      // walking pace: under 0.3 m/s
  EXPECT_LT(max_turn, 0.06);      // under 35 deg/s
}

TEST(CameraMotion, UnknownTrajectoryNamesTheChoices) {
  try {
    CameraMotion::create("spiral", kData, 0);
    FAIL() << "expected an error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("halfsphere"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("loop"), std::string::npos);
  }
}

}  // namespace
}  // namespace stillslam::sim
