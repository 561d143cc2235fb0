// Trajectory readers and writers: round trips, format detection, real files
// from ../shared, and errors naming file and line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include <unistd.h>

#include "stillslam/core/error.h"
#include "stillslam/io/trajectory.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / ("stillslam_test_trajectory_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

fs::path write_text(const std::string& name, const std::string& text) {
  const fs::path path = temp_dir() / name;
  std::ofstream(path) << text;
  return path;
}

fs::path shared_trajectories() { return fs::path(STILLSLAM_SHARED_DIR) / "data" / "trajectories"; }

#define SKIP_WITHOUT_SHARED()                                                                                 \
  if (!fs::exists(shared_trajectories())) {                                                                   \
    GTEST_SKIP() << "shared data not found at " << shared_trajectories() << "; real-file tests need it"; \
  }

Trajectory random_trajectory(std::size_t n, double t0) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Trajectory trajectory;
  for (std::size_t i = 0; i < n; ++i) {
    StampedPose pose;
    pose.timestamp = t0 + 0.033 * static_cast<double>(i) + 1e-4 * u(rng);
    pose.T_world_cam.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
    pose.T_world_cam.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 10.0;
    trajectory.push_back(pose);
  }
  return trajectory;
}

void expect_same_poses(const Trajectory& a, const Trajectory& b, double stamp_tolerance) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a[i].timestamp, b[i].timestamp, stamp_tolerance) << "pose " << i;
    EXPECT_LT((a[i].T_world_cam.matrix() - b[i].T_world_cam.matrix()).cwiseAbs().maxCoeff(), 1e-12) << "pose " << i;
  }
}

TEST(Trajectory, TumRoundTripIsExact) {
  const Trajectory original = random_trajectory(50, 1311868164.363181);
  const fs::path path = temp_dir() / "tum.txt";
  write_trajectory(path, original, TrajectoryFormat::Tum);
  EXPECT_EQ(detect_trajectory_format(path), TrajectoryFormat::Tum);
  const Trajectory read = read_trajectory(path);
  expect_same_poses(original, read, 0.0);  // shortest round-trip text: stamps bit-identical
}

TEST(Trajectory, EurocRoundTripKeepsNanoseconds) {
  const Trajectory original = random_trajectory(50, 1403715274.312143104);
  const fs::path path = temp_dir() / "euroc.csv";
  write_trajectory(path, original, TrajectoryFormat::Euroc);
  EXPECT_EQ(detect_trajectory_format(path), TrajectoryFormat::Euroc);
  expect_same_poses(original, read_trajectory(path), 1e-6);
}

TEST(Trajectory, KittiRoundTripUsesIndexOrTimesFile) {
  const Trajectory original = random_trajectory(20, 0.0);
  const fs::path path = temp_dir() / "kitti.txt";
  write_trajectory(path, original, TrajectoryFormat::Kitti);
  EXPECT_EQ(detect_trajectory_format(path), TrajectoryFormat::Kitti);
  const Trajectory by_index = read_trajectory(path);
  ASSERT_EQ(by_index.size(), 20u);
  EXPECT_EQ(by_index[7].timestamp, 7.0);
  std::string times;
  for (const auto& pose : original) times += std::to_string(pose.timestamp) + "\n";
  const Trajectory timed = read_kitti_trajectory(path, write_text("times.txt", times));
  expect_same_poses(original, timed, 1e-6);
}

TEST(Trajectory, WriterFlushesEveryPose) {
  const Trajectory original = random_trajectory(3, 100.0);
  const fs::path path = temp_dir() / "appended.txt";
  TrajectoryWriter writer(path, TrajectoryFormat::Tum);
  for (const auto& pose : original) writer.write(pose);
  // Read while the writer is still open: everything must already be on disk.
  EXPECT_EQ(writer.count(), 3u);
  expect_same_poses(original, read_trajectory(path), 0.0);
}

TEST(Trajectory, TumNanosecondStampsAndWFirstHeader) {
  const fs::path path = write_text("ns_wfirst.txt",
                                   "# timestamp x y z qw qx qy qz\n"
                                   "1403715274312143104 1 2 3 0.5 0.5 0.5 0.5\n"
                                   "1403715274362142976 1 2 3 0 0 0 1\n");
  const Trajectory t = read_trajectory(path);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_NEAR(t[0].timestamp, 1403715274.312143104, 1e-6);
  EXPECT_NEAR(t[1].timestamp - t[0].timestamp, 0.049999872, 1e-6);
  // w first: the second pose is a 180 degree turn about z.
  EXPECT_NEAR(t[1].T_world_cam.linear()(0, 0), -1.0, 1e-12);
  EXPECT_NEAR(t[0].T_world_cam.linear()(0, 2), 1.0, 1e-12);  // (0.5,0.5,0.5,0.5) maps z -> x
}

TEST(Trajectory, TumQuaternionsAreNormalised) {
  const Trajectory t = read_trajectory(write_text("rounded.txt", "1.0 0 0 0 0 0 0.7071 0.7071\n"));
  EXPECT_NEAR(Eigen::Quaterniond(t[0].T_world_cam.linear()).norm(), 1.0, 1e-15);
  EXPECT_NEAR((t[0].T_world_cam.linear() * t[0].T_world_cam.linear().transpose() - Eigen::Matrix3d::Identity()).norm(),
              0.0, 1e-12);
}

TEST(Trajectory, ToleratesCrlfPaddingAndHeaderlessCsv) {
  const Trajectory crlf = read_trajectory(write_text("crlf.txt", "# t x y z qx qy qz qw\r\n1.5 1 2 3 0 0 0 1\r\n"));
  ASSERT_EQ(crlf.size(), 1u);
  EXPECT_EQ(crlf[0].timestamp, 1.5);
  const fs::path csv = write_text("padded.csv", "timestamp, x, y, z, qw, qx, qy, qz\n1000000000, 1, 2, 3, 1, 0, 0, 0\n");
  EXPECT_EQ(detect_trajectory_format(csv), TrajectoryFormat::Euroc);
  const Trajectory padded = read_trajectory(csv);
  ASSERT_EQ(padded.size(), 1u);
  EXPECT_EQ(padded[0].timestamp, 1.0);
  EXPECT_EQ(padded[0].T_world_cam.translation(), Eigen::Vector3d(1, 2, 3));
}

TEST(Trajectory, CsvHeaderDecidesQuaternionOrderAndSecondStamps) {
  // x-first columns named in the header, stamps in seconds with a fraction.
  const fs::path csv = write_text("xyzw.csv", "#t,x,y,z,qx,qy,qz,qw\n12.25,1,2,3,0,0,1,0\n");
  const Trajectory t = read_trajectory(csv);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].timestamp, 12.25);
  EXPECT_NEAR(t[0].T_world_cam.linear()(0, 0), -1.0, 1e-12);  // 180 degrees about z
  // Comment lines made only of '#' are not headers.
  EXPECT_EQ(read_trajectory(write_text("hashes.txt", "##\n#\n1 0 0 0 0 0 0 1\n")).size(), 1u);
}

TEST(Trajectory, MalformedLineNamesFileAndLine) {
  const fs::path path = write_text("broken.txt", "# header\n1.0 0 0 0 0 0 0 1\n2.0 0 0 zero 0 0 0 1\n");
  try {
    read_trajectory(path);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find("line 3"), std::string::npos) << message;
    EXPECT_NE(message.find("zero"), std::string::npos) << message;
  }
  const fs::path short_line = write_text("short.txt", "1.0 0 0 0 0 0 0 1\n2.0 0 0 0 0 0 0 1\n3.0 0 0 0\n");
  try {
    read_trajectory(short_line, TrajectoryFormat::Tum);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
  }
  const fs::path kitti = write_text("broken_kitti.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1\n");
  try {
    read_trajectory(kitti);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos) << e.what();
  }
}

TEST(Trajectory, MissingEmptyAndUnknownFilesFailClearly) {
  EXPECT_THROW(read_trajectory(temp_dir() / "does_not_exist.txt"), Error);
  EXPECT_THROW(read_trajectory(write_text("empty.txt", "# only a comment\n\n")), Error);
  EXPECT_THROW(detect_trajectory_format(write_text("five.txt", "1 2 3 4 5\n")), Error);
  EXPECT_THROW(read_kitti_trajectory(write_text("k.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n"), write_text("t.txt", "0\n1\n")),
               Error);
  EXPECT_THROW(parse_trajectory_format("bag"), Error);
  EXPECT_EQ(parse_trajectory_format("EuRoC"), TrajectoryFormat::Euroc);
}

TEST(TrajectoryRealFiles, DetectsFormats) {
  SKIP_WITHOUT_SHARED();
  const fs::path d = shared_trajectories();
  EXPECT_EQ(detect_trajectory_format(d / "fr2_desk_groundtruth.txt"), TrajectoryFormat::Tum);
  EXPECT_EQ(detect_trajectory_format(d / "V102.txt"), TrajectoryFormat::Tum);
  EXPECT_EQ(detect_trajectory_format(d / "KITTI_00_gt.txt"), TrajectoryFormat::Kitti);
  EXPECT_EQ(detect_trajectory_format(d / "kitti_poses/00/00.txt"), TrajectoryFormat::Kitti);
  EXPECT_EQ(detect_trajectory_format(d / "kitti_poses/00/groundtruth.txt"), TrajectoryFormat::Tum);
  EXPECT_EQ(detect_trajectory_format(d / "V102_groundtruth.csv"), TrajectoryFormat::Euroc);
  EXPECT_EQ(detect_trajectory_format(d / "euroc_left_cam_gt/MH01_GT.txt"), TrajectoryFormat::Euroc);
}

TEST(TrajectoryRealFiles, ReadsTumGroundTruth) {
  SKIP_WITHOUT_SHARED();
  const fs::path path = shared_trajectories() / "fr2_desk_groundtruth.txt";
  // Stamp 1311868229.576 appears twice with different poses: with DuplicateStamps::Error an Error naming both lines.
  try {
    read_trajectory(path, {}, DuplicateStamps::Error);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("lines 10862 and 10863"), std::string::npos) << e.what();
  }
  const Trajectory t = read_trajectory(path);  // KeepLast, the default
  ASSERT_EQ(t.size(), 20956u);
  const auto repeated = std::find_if(t.begin(), t.end(), [](const StampedPose& p) { return p.timestamp == 1311868229.576; });
  ASSERT_NE(repeated, t.end());
  EXPECT_DOUBLE_EQ(repeated->T_world_cam.translation().x(), 1.4044);  // line 10863, the later one
  EXPECT_DOUBLE_EQ(t[0].timestamp, 1311868163.8697);
  EXPECT_NEAR(t[0].T_world_cam.translation().x(), -0.1357, 1e-12);
  const Eigen::Quaterniond q = Eigen::Quaterniond(-0.4101, 0.6453, -0.5498, 0.3363).normalized();
  EXPECT_LT((t[0].T_world_cam.linear() - q.toRotationMatrix()).norm(), 1e-12);
}

TEST(TrajectoryRealFiles, ReadsEurocCsvWithExtraColumns) {
  SKIP_WITHOUT_SHARED();
  const Trajectory t = read_trajectory(shared_trajectories() / "V102_groundtruth.csv");
  ASSERT_EQ(t.size(), 16702u);
  EXPECT_NEAR(t[0].timestamp, 1403715524.907143168, 1e-6);
  EXPECT_NEAR(t[0].T_world_cam.translation().y(), 1.996773, 1e-12);
  const Eigen::Quaterniond q = Eigen::Quaterniond(0.161996, 0.789985, -0.205376, 0.554528).normalized();
  EXPECT_LT((t[0].T_world_cam.linear() - q.toRotationMatrix()).norm(), 1e-12);
}

TEST(TrajectoryRealFiles, ReadsOrbSlam3LeftCameraGroundTruth) {
  SKIP_WITHOUT_SHARED();
  // ns stamps written as "1403715274312143104.0000000000", header q_RS_w first.
  const fs::path path = fs::path(STILLSLAM_SHARED_DIR) / "data/euroc_V1_01_micro/V101_GT_leftcam_from_ORB_SLAM3_eval.txt";
  const Trajectory t = read_trajectory(path);
  ASSERT_EQ(t.size(), 2871u);
  EXPECT_NEAR(t[0].timestamp, 1403715274.312143104, 1e-6);
  EXPECT_NEAR(t[1].timestamp - t[0].timestamp, 0.049999872, 1e-6);
  const Eigen::Quaterniond q = Eigen::Quaterniond(0.4259596512, 0.6262011737, -0.5441421096, 0.361026079545).normalized();
  EXPECT_LT((t[0].T_world_cam.linear() - q.toRotationMatrix()).norm(), 1e-12);
}

TEST(TrajectoryRealFiles, ReadsKittiWithTimes) {
  SKIP_WITHOUT_SHARED();
  const fs::path d = shared_trajectories();
  const Trajectory t = read_kitti_trajectory(d / "KITTI_00_gt.txt", d / "KITTI_00_gt_times.txt");
  ASSERT_EQ(t.size(), 4541u);
  EXPECT_DOUBLE_EQ(t[1].timestamp, 0.1037359);
  EXPECT_NEAR(t[1].T_world_cam.translation().z(), 0.8586941, 1e-12);
  // pyslam's 9-column variant of the same poses reads as TUM with equal positions.
  const Trajectory tum = read_trajectory(d / "kitti_poses/00/groundtruth.txt");
  ASSERT_EQ(tum.size(), 4541u);
  EXPECT_LT((tum[100].T_world_cam.translation() - t[100].T_world_cam.translation()).norm(), 1e-6);
  EXPECT_NEAR(tum[100].timestamp, t[100].timestamp, 1e-6);
}

}  // namespace
}  // namespace stillslam
