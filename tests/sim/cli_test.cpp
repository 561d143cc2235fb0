// `stillslam simulate` end to end through the binary (skipped when the binary
// has not been built, e.g. when only test_sim was built).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <sys/wait.h>

namespace {
namespace fs = std::filesystem;

int run(const std::string& args, const fs::path& log) {
  const std::string cmd = std::string(STILLSLAM_BINARY) + " simulate " + args + " > " + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(SimulateCommand, WritesRgbdAndStereoLayouts) {
  if (!fs::exists(STILLSLAM_BINARY)) GTEST_SKIP() << STILLSLAM_BINARY << " not built";
  const fs::path dir = fs::temp_directory_path() / ("stillslam_sim_cli_" + std::to_string(std::random_device{}()));
  const fs::path log = dir.string() + ".log";
  ASSERT_EQ(run("--out " + dir.string() + " --trajectory rpy --frames 3 --width 160 --height 120 --stereo "
                "--people 1 --noise 1 --data-dir " STILLSLAM_SOURCE_DIR "/data",
                log),
            0)
      << read(log);
  for (const char* f : {"rgb.txt", "depth.txt", "associations.txt", "groundtruth.txt", "settings.yaml",
                        "settings_stereo.yaml", "mav0/cam0/data.csv", "mav0/cam1/data.csv",
                        "mav0/cam0/sensor.yaml", "mav0/cam1/sensor.yaml",
                        "mav0/state_groundtruth_estimate0/data.csv"}) {
    EXPECT_TRUE(fs::is_regular_file(dir / f)) << f;
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "mav0" / "cam1" / "data"), fs::directory_iterator{}), 3);
  fs::remove_all(dir);
  fs::remove(log);
}

TEST(SimulateCommand, BadTrajectoryFailsWithAClearMessage) {
  if (!fs::exists(STILLSLAM_BINARY)) GTEST_SKIP() << STILLSLAM_BINARY << " not built";
  const fs::path dir = fs::temp_directory_path() / ("stillslam_sim_cli_bad_" + std::to_string(std::random_device{}()));
  const fs::path log = dir.string() + ".log";
  EXPECT_EQ(run("--out " + dir.string() + " --trajectory no_such_path.txt --data-dir " STILLSLAM_SOURCE_DIR "/data",
                log),
            1);
  EXPECT_NE(read(log).find("halfsphere"), std::string::npos) << read(log);
  fs::remove_all(dir);
  fs::remove(log);
}

TEST(SimulateCommand, BadCrowdOrOccluderWindowNamesTheFlag) {
  if (!fs::exists(STILLSLAM_BINARY)) GTEST_SKIP() << STILLSLAM_BINARY << " not built";
  const fs::path dir = fs::temp_directory_path() / ("stillslam_sim_cli_win_" + std::to_string(std::random_device{}()));
  const fs::path log = dir.string() + ".log";
  for (const std::string& window : {std::string("--crowd 3:x"), std::string("--crowd 3:0"), std::string("--occlude -1")}) {
    EXPECT_EQ(run("--out " + dir.string() + " " + window + " --data-dir " STILLSLAM_SOURCE_DIR "/data", log), 1)
        << window;
    EXPECT_NE(read(log).find(window.substr(0, window.find(' '))), std::string::npos) << read(log);
    EXPECT_FALSE(fs::exists(dir / "rgb.txt"));
  }
  // The still person on chair 1 and the pushed chair cannot both be there.
  EXPECT_EQ(run("--out " + dir.string() + " --moved-chair --still-people 2 --data-dir " STILLSLAM_SOURCE_DIR "/data", log),
            1);
  EXPECT_NE(read(log).find("--still-people 1"), std::string::npos) << read(log);
  fs::remove_all(dir);
  fs::remove(log);
}

}  // namespace
