// Usage errors of `stillslam ros2` and `stillslam ros2-replay`: one message
// naming the option and the fix, exit 1, before any DDS traffic.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

#include "common/error_text.h"
#include "common/run_stillslam.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

const std::string kSource = STILLSLAM_SOURCE_DIR;

std::string out_dir() { return (fs::temp_directory_path() / ("stillslam_ros2_cli_" + std::to_string(::getpid()))).string(); }

TEST(Ros2Cli, TopicsOfTheOtherSensorAreRefused) {
  REQUIRE_STILLSLAM_BINARY();
  const test::CommandRun r = test::run_stillslam(
      "ros2 --config " + kSource + "/config/tum_fr3.yaml --left cam/left --output " + out_dir(), true);
  EXPECT_EQ(WEXITSTATUS(r.status), 1) << r.out;
  EXPECT_TRUE(test::contains(r.out, "describes an RGB-D camera: give --rgb/--depth, not --left/--right")) << r.out;
}

TEST(Ros2Cli, DomainOutOfRangeIsRefused) {
  REQUIRE_STILLSLAM_BINARY();
  const test::CommandRun r = test::run_stillslam(
      "ros2 --config " + kSource + "/config/euroc.yaml --domain 300 --output " + out_dir(), true);
  EXPECT_EQ(WEXITSTATUS(r.status), 1) << r.out;
  EXPECT_TRUE(test::contains(r.out, "--domain 300 is out of range: DDS domain ids are 0..232")) << r.out;
  fs::remove_all(out_dir());
}

TEST(Ros2Cli, ReplayWithoutANodeStopsAfterItsTimeout) {
  REQUIRE_STILLSLAM_BINARY();
  const fs::path clip = fs::path(STILLSLAM_SHARED_DIR) / "data" / "euroc_V1_01_micro";
  if (!fs::exists(clip)) GTEST_SKIP() << clip << " is absent (../shared is not on this machine)";
  const std::string domain = std::to_string(201 + ::getpid() % 30);  // each test its own range of domains
  const test::CommandRun r = test::run_stillslam("ros2-replay " + clip.string() + " --config " + kSource +
                                                     "/config/euroc.yaml --wait-subscriber 0.5 --domain " + domain,
                                                 true);
  EXPECT_EQ(WEXITSTATUS(r.status), 1) << r.out;
  EXPECT_TRUE(test::contains(r.out, "no ROS 2 node matched rt/camera/left/image_raw on DDS domain " + domain +
                                        " (loopback) within 0.5 s")) << r.out;
}

}  // namespace
}  // namespace stillslam
