// TrajectoryWriter (the live trajectory of `run`): whole lines only, also when
// the disk fills up mid-line; write_trajectory replaces a file only whole.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "io/temp_dir.h"
#include "stillslam/core/error.h"
#include "stillslam/io/trajectory.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

StampedPose pose_at(int i) {
  StampedPose p;
  p.timestamp = 1341846313.592026 + 0.033 * i;
  p.T_world_cam.linear() = Eigen::AngleAxisd(0.01 * i + 0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  p.T_world_cam.translation() = Eigen::Vector3d(0.1 * i + 0.123456789, -0.2 * i, 1.0 / (i + 3));
  return p;
}

TEST(TrajectoryWriter, EveryPoseIsOnDiskAsAWholeLineAtOnce) {
  test::TempDir dir;
  const fs::path path = dir.path() / "live.txt";
  TrajectoryWriter writer(path);
  std::string expected;
  for (int i = 0; i < 4; ++i) {
    writer.write(pose_at(i));
    expected += format_trajectory_line(pose_at(i), TrajectoryFormat::Tum) + '\n';
    EXPECT_EQ(read(path), expected) << "after pose " << i;  // no buffering in the process
  }
  EXPECT_EQ(writer.count(), 4u);
  EXPECT_FALSE(writer.failed());
}

// A full disk without root: RLIMIT_FSIZE in a child process (SIGXFSZ
// ignored) stops the file in the middle of the 4th line. The writer cuts that
// line off, warns once naming the file and the cause, and writes nothing more:
// the file holds exactly 3 whole poses and reads back.
TEST(TrajectoryWriter, AFullDiskCutsBackToTheLastWholeLineAndWarnsOnce) {
  test::TempDir dir;
  const fs::path path = dir.path() / "trajectory_live.txt";
  const fs::path log = dir.path() / "log.txt";
  std::size_t three_lines = 0;
  for (int i = 0; i < 3; ++i) three_lines += format_trajectory_line(pose_at(i), TrajectoryFormat::Tum).size() + 1;
  const rlim_t limit = three_lines + 20;  // the 4th line is longer than 20 bytes
  std::ofstream(log).close();  // created before the limit applies
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    std::freopen(log.c_str(), "a", stdout);  // spdlog's default logger writes to stdout
    const rlimit r{limit, limit};
    ::setrlimit(RLIMIT_FSIZE, &r);
    TrajectoryWriter writer(path);
    for (int i = 0; i < 10; ++i) writer.write(pose_at(i));
    std::fflush(stdout);
    std::_Exit(writer.failed() ? static_cast<int>(writer.count()) : 100);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 3);  // failed, 3 poses written
  EXPECT_EQ(fs::file_size(path), three_lines);
  const Trajectory back = read_trajectory(path);
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back[2].timestamp, pose_at(2).timestamp);
  const std::string text = read(log);
  const std::string warning = "writing trajectory file " + path.string() + " failed (File too large)";
  const auto first = text.find(warning);
  EXPECT_NE(first, std::string::npos) << text;
  EXPECT_EQ(text.find(warning, first + 1), std::string::npos) << "warned more than once:\n" << text;
  EXPECT_NE(text.find("the final trajectory is still written at the end"), std::string::npos) << text;
}

TEST(TrajectoryWriter, WriteTrajectoryIntoAFolderNamesTheCauseAndLeavesNothing) {
  test::TempDir dir;
  fs::create_directories(dir.path() / "trajectory.txt");
  try {
    write_trajectory(dir.path() / "trajectory.txt", {pose_at(0)});
    FAIL() << "writing over a folder must fail";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find((dir.path() / "trajectory.txt").string() + ": Is a directory"),
              std::string::npos)
        << e.what();
  }
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, 1u);
}

}  // namespace
}  // namespace stillslam
