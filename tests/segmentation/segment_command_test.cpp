// `stillslam segment` end to end, through the built binary.
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <sstream>
#include <string>

#include <sys/wait.h>

#include "common/run_stillslam.h"
#include "segmentation/test_data.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

using test::CommandRun;

CommandRun run(const std::string& args) { return test::run_stillslam(args, false); }

TEST(SegmentCommand, PrintsOneJsonLinePerDetectionAndWritesMasks) {
  REQUIRE_STILLSLAM_BINARY()
  const fs::path out = fs::temp_directory_path() / "stillslam_segment_command_test";
  fs::remove_all(out);
  const CommandRun r = run("segment --model " + test::shipped_model() + " --image " + test::bus_image() + " --out " +
                    out.string() + " --threads 1");
  ASSERT_EQ(r.status, 0) << r.out;
  const std::regex line(
      R"re(\{"class": "([a-z ]+)", "class_id": (\d+), "score": (0\.\d+), "box": \[([\d.]+), ([\d.]+), ([\d.]+), ([\d.]+)\]\})re");
  std::istringstream lines(r.out);
  std::string l;
  int persons = 0, total = 0;
  while (std::getline(lines, l)) {
    std::smatch m;
    ASSERT_TRUE(std::regex_match(l, m, line)) << l;
    ++total;
    if (m[1] == "person") ++persons;
    if (total == 1) {  // highest score first: the person at x 220..346 (see yolo_reference_test)
      EXPECT_EQ(m[2], "0");
      EXPECT_NEAR(std::stod(m[4]), 220.2, 0.2);
      EXPECT_NEAR(std::stod(m[7]), 855.4, 0.2);
    }
  }
  EXPECT_EQ(total, 5);
  EXPECT_EQ(persons, 3);
  // Union of the dynamic class (person) and one mask per instance, frame-sized.
  const cv::Mat union_mask = cv::imread((out / "masks" / "bus.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(union_mask.size(), cv::Size(810, 1080));
  EXPECT_NEAR(cv::countNonZero(union_mask), 33990 + 50663 + 20566, 0.02 * 105219);
  EXPECT_TRUE(test::exists((out / "instances" / "bus_00_person.png").string()));
  EXPECT_TRUE(test::exists((out / "instances" / "bus_04_truck.png").string()));
  EXPECT_TRUE(test::exists((out / "overlays" / "bus.jpg").string()));
  fs::remove_all(out);
}

TEST(SegmentCommand, ClassFilterAndErrors) {
  REQUIRE_STILLSLAM_BINARY()
  const fs::path out = fs::temp_directory_path() / "stillslam_segment_command_test2";
  const std::string base = "segment --model " + test::shipped_model() + " --image " + test::bus_image() + " --out " +
                           out.string() + " --threads 1";
  const CommandRun buses = run(base + " --classes bus,7");
  ASSERT_EQ(buses.status, 0);
  EXPECT_EQ(std::count(buses.out.begin(), buses.out.end(), '\n'), 2);  // bus + truck, no people
  EXPECT_EQ(buses.out.find("person"), std::string::npos);
  EXPECT_NE(run(base + " --classes unicorn").status, 0);
  EXPECT_NE(run("segment --model /no/such/model.onnx --image " + test::bus_image() + " --out " + out.string()).status, 0);
  EXPECT_NE(run("segment --model " + test::shipped_model() + " --image /no/such.jpg --out " + out.string()).status, 0);
  fs::remove_all(out);
}

// A folder with a corrupt image: `segment --input` stops at it, naming it,
// unless --skip-bad-frames, which warns with its name and segments the rest.
TEST(SegmentCommand, SkipBadFramesGoesOnPastACorruptImage) {
  REQUIRE_STILLSLAM_BINARY()
  const fs::path dir = fs::temp_directory_path() / "stillslam_segment_skip_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "images");
  fs::copy_file(test::bus_image(), dir / "images" / "a.jpg");
  std::ofstream(dir / "images" / "b.png") << "not a png";
  fs::copy_file(test::bus_image(), dir / "images" / "c.jpg");
  const std::string base = "segment --model " + test::shipped_model() + " --input " + (dir / "images").string() +
                           " --out " + (dir / "out").string() + " --threads 1";
  const CommandRun stops = test::run_stillslam(base, true);
  EXPECT_NE(stops.status, 0);
  EXPECT_NE(stops.out.find("b.png"), std::string::npos) << stops.out;
  EXPECT_FALSE(fs::exists(dir / "out" / "masks" / "c.png"));

  const CommandRun skips = test::run_stillslam(base + " --skip-bad-frames", true);
  EXPECT_EQ(skips.status, 0) << skips.out;
  EXPECT_NE(skips.out.find("skipping bad image (1 skipped so far): " + (dir / "images" / "b.png").string()),
            std::string::npos)
      << skips.out;
  EXPECT_NE(skips.out.find("segment: 1 of 3 image(s) skipped"), std::string::npos) << skips.out;
  EXPECT_TRUE(fs::exists(dir / "out" / "masks" / "a.png"));
  EXPECT_TRUE(fs::exists(dir / "out" / "masks" / "c.png"));
  EXPECT_FALSE(fs::exists(dir / "out" / "masks" / "b.png"));
  fs::remove_all(dir);
}

// --dilation and --threads take Segmentation.maskDilation's and .threads' limits
// (a dilation of 1e6 ended in std::bad_alloc, 100000 threads crashed at exit).
TEST(SegmentCommand, DilationAndThreadsOutOfRangeAreNamed) {
  REQUIRE_STILLSLAM_BINARY()
  const fs::path out = fs::temp_directory_path() / "stillslam_segment_limits_test";
  const std::string base = "segment --model " + test::shipped_model() + " --image " + test::bus_image() + " --out " +
                           out.string();
  const CommandRun dilation = test::run_stillslam(base + " --dilation 1000000", true);
  EXPECT_EQ(WEXITSTATUS(dilation.status), 1);
  EXPECT_NE(dilation.out.find("--dilation is 1000000: must be in [0, 256] pixels"), std::string::npos)
      << dilation.out;
  const CommandRun threads = test::run_stillslam(base + " --threads 100000", true);
  EXPECT_EQ(WEXITSTATUS(threads.status), 1);
  EXPECT_NE(threads.out.find("--threads is 100000: must be in [0, "), std::string::npos) << threads.out;
  fs::remove_all(out);
}

}  // namespace
}  // namespace stillslam
