// `stillslam run` end to end through the binary on a tiny synthetic sequence
// written to disk: output files, their line counts, stats.json keys, errors.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "stillslam/io/trajectory.h"
#include "stillslam/sim/sequence_writer.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

std::size_t count_lines(const fs::path& p) {
  std::ifstream in(p);
  std::size_t n = 0;
  std::string line;
  while (std::getline(in, line)) n += (!line.empty() && line[0] != '#') ? 1 : 0;
  return n;
}

TEST(RunCommand, WritesTrajectoriesAndStats) {
  const fs::path binary(STILLSLAM_BINARY);
  if (!fs::exists(binary)) GTEST_SKIP() << "build the stillslam binary first (" << binary << ")";
  const fs::path dir = fs::temp_directory_path() / "stillslam_test_run_command";
  fs::remove_all(dir);
  sim::SimulationOptions opts;
  opts.trajectory = "walking_xyz";
  opts.frames = 30;
  opts.width = 400;
  opts.height = 300;
  opts.no_people = true;
  opts.supersampling = 1;
  opts.data_dir = fs::path(STILLSLAM_SOURCE_DIR) / "data";
  const sim::SequenceSummary seq = sim::write_sequence(dir / "seq", opts);
  const fs::path out = dir / "out";
  const std::string cmd = binary.string() + " run --config " + seq.settings.string() + " --input " +
                          (dir / "seq").string() + " --output " + out.string() +
                          " --no-segmentation --deterministic > " + (dir / "log.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << "see " << (dir / "log.txt");
  for (const char* f : {"trajectory.txt", "trajectory_live.txt", "keyframes.txt", "stats.json"}) {
    EXPECT_TRUE(fs::exists(out / f)) << f;
  }
  std::ifstream stats_file(out / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(stats_file);
  const std::size_t tracked = stats["summary"]["tracked"].get<std::size_t>();
  EXPECT_EQ(stats["frames"].size(), 30u);
  EXPECT_EQ(tracked, 30u);
  EXPECT_EQ(count_lines(out / "trajectory.txt"), tracked);
  EXPECT_EQ(count_lines(out / "trajectory_live.txt"), tracked);
  EXPECT_GE(count_lines(out / "keyframes.txt"), 1u);
  EXPECT_LT(stats["summary"]["ate_rmse"].get<double>(), 0.01);
  for (const char* key : {"features_before_filter", "features_after_filter", "matches", "inliers", "detections",
                          "mask_coverage", "state", "timestamp"}) {
    EXPECT_TRUE(stats["frames"][0].contains(key)) << key;
  }
  for (const char* key : {"extraction", "segmentation_wait", "tracking", "total"}) {
    EXPECT_TRUE(stats["frames"][0]["times_ms"].contains(key)) << key;
  }
  // The final trajectory reads back as TUM with increasing stamps.
  const Trajectory t = read_trajectory(out / "trajectory.txt");
  ASSERT_EQ(t.size(), tracked);
  for (std::size_t i = 1; i < t.size(); ++i) EXPECT_GT(t[i].timestamp, t[i - 1].timestamp);

  // A missing dataset folder: clear error, non-zero exit.
  const std::string bad = binary.string() + " run --config " + seq.settings.string() + " --input " +
                          (dir / "missing").string() + " --output " + (dir / "out2").string() + " > " +
                          (dir / "log2.txt").string() + " 2>&1";
  EXPECT_NE(std::system(bad.c_str()), 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace stillslam
