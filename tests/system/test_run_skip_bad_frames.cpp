// `stillslam run --skip-bad-frames` through the binary: a missing frame ends
// the run without the flag; with it the run goes on, warns naming the file
// and counts the frame in stats.json.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "stillslam/sim/sequence_writer.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(RunCommand, SkipBadFramesGoesOnPastAMissingFrame) {
  const fs::path binary(STILLSLAM_BINARY);
  if (!fs::exists(binary)) GTEST_SKIP() << "build the stillslam binary first (" << binary << ")";
  const fs::path dir = fs::temp_directory_path() / "stillslam_test_run_skip_bad_frames";
  fs::remove_all(dir);
  sim::SimulationOptions opts;
  opts.trajectory = "walking_xyz";
  opts.frames = 20;
  opts.width = 400;
  opts.height = 300;
  opts.no_people = true;
  opts.supersampling = 1;
  opts.data_dir = fs::path(STILLSLAM_SOURCE_DIR) / "data";
  const sim::SequenceSummary seq = sim::write_sequence(dir / "seq", opts);
  std::vector<fs::path> rgb;
  for (const auto& e : fs::directory_iterator(dir / "seq" / "rgb")) rgb.push_back(e.path());
  std::sort(rgb.begin(), rgb.end());
  ASSERT_EQ(rgb.size(), 20u);
  const fs::path missing = rgb[12];
  fs::remove(missing);

  const std::string base = binary.string() + " run --config " + seq.settings.string() + " --input " +
                           (dir / "seq").string() + " --no-segmentation --deterministic --vocabulary none";
  const std::string stops = base + " --output " + (dir / "out1").string() + " > " + (dir / "log1.txt").string() +
                            " 2>&1";
  EXPECT_NE(std::system(stops.c_str()), 0);
  EXPECT_NE(read_text(dir / "log1.txt").find(missing.string() + ": image file is missing"), std::string::npos)
      << read_text(dir / "log1.txt");

  const std::string skips = base + " --skip-bad-frames --output " + (dir / "out2").string() + " > " +
                            (dir / "log2.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(skips.c_str()), 0) << read_text(dir / "log2.txt");
  const std::string log = read_text(dir / "log2.txt");
  EXPECT_NE(log.find("skipping bad frame 12 (1 skipped so far): " + missing.string() + ": image file is missing"),
            std::string::npos)
      << log;
  std::ifstream stats_file(dir / "out2" / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(stats_file);
  EXPECT_EQ(stats["summary"]["skipped_frames"].get<std::size_t>(), 1u);
  EXPECT_EQ(stats["frames"].size(), 19u);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace stillslam
