// `stillslam run` end to end through the binary on a tiny synthetic sequence
// written to disk: output files, their line counts, stats.json keys, errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include "stillslam/io/camera_settings.h"
#include "stillslam/io/trajectory.h"
#include "common/small_sequence.h"
#include "stillslam/sim/sequence_writer.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

using test::write_small_sequence;

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
  const sim::SequenceSummary seq = write_small_sequence(dir, 30, false);
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
  // The map starts at frame 3 from frame 0 (the unmasked start check); frames 0-2 are posed then.
  for (std::size_t i = 0; i < 30; ++i) {
    EXPECT_TRUE(stats["frames"][i]["has_pose"].get<bool>()) << i;
    EXPECT_EQ(stats["frames"][i]["posed_at_start"].get<bool>(), i < 3) << i;
    EXPECT_EQ(stats["frames"][i]["state"].get<std::string>(), i < 3 ? "not_initialized" : "ok") << i;
  }
  EXPECT_EQ(stats["frames"][3]["reason"].get<std::string>().rfind("map started at frame 0", 0), 0u)
      << stats["frames"][3]["reason"];
  const Trajectory live = read_trajectory(out / "trajectory_live.txt");
  for (std::size_t i = 1; i < live.size(); ++i) EXPECT_GT(live[i].timestamp, live[i - 1].timestamp);
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

// A user's ORB-SLAM3 RGB-D file as it is (old-style keys, Viewer.*, no
// Segmentation.*) runs with segmentation on, using the shipped model.
TEST(RunCommand, OrbSlam3SettingsRunWithTheShippedModel) {
  const fs::path binary(STILLSLAM_BINARY);
  if (!fs::exists(binary)) GTEST_SKIP() << "build the stillslam binary first (" << binary << ")";
  const fs::path dir = fs::temp_directory_path() / "stillslam_test_run_orbslam3_settings";
  fs::remove_all(dir);
  const sim::SequenceSummary seq = write_small_sequence(dir, 6, true);
  const CameraCalibration c = load_camera_settings(seq.settings).camera;
  const fs::path config = dir / "TUM3.yaml";
  std::ofstream(config) << "%YAML:1.0\n"
                        << "Camera.fx: " << c.fx << "\nCamera.fy: " << c.fy << "\nCamera.cx: " << c.cx
                        << "\nCamera.cy: " << c.cy << "\n"
                        << "Camera.k1: 0.0\nCamera.k2: 0.0\nCamera.p1: 0.0\nCamera.p2: 0.0\n"
                        << "Camera.width: " << c.width << "\nCamera.height: " << c.height << "\n"
                        << "Camera.fps: 30.0\nCamera.bf: " << 0.0747 * c.fx << "\nCamera.RGB: 1\n"
                        << "ThDepth: 40.0\nDepthMapFactor: 5000.0\n"
                        << "ORBextractor.nFeatures: 1000\nORBextractor.scaleFactor: 1.2\nORBextractor.nLevels: 8\n"
                        << "ORBextractor.iniThFAST: 20\nORBextractor.minThFAST: 7\n"
                        << "Viewer.KeyFrameSize: 0.05\nViewer.KeyFrameLineWidth: 1\nViewer.GraphLineWidth: 0.9\n"
                        << "Viewer.PointSize:2\nViewer.CameraSize: 0.08\nViewer.CameraLineWidth: 3\n"
                        << "Viewer.ViewpointX: 0\nViewer.ViewpointY: -0.7\nViewer.ViewpointZ: -1.8\n"
                        << "Viewer.ViewpointF: 500\n";
  const fs::path out = dir / "out";
  const fs::path log = dir / "log.txt";
  const std::string cmd = binary.string() + " run --config " + config.string() + " --input " +
                          (dir / "seq").string() + " --output " + out.string() + " --deterministic --vocabulary none > " +
                          log.string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(log);
  EXPECT_NE(read_text(log).find("segmentation on"), std::string::npos) << read_text(log);
  std::ifstream stats_file(out / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(stats_file);
  EXPECT_TRUE(stats["segmentation"].get<bool>());
  ASSERT_EQ(stats["frames"].size(), 6u);
  for (const nlohmann::json& frame : stats["frames"]) {
    EXPECT_TRUE(frame.contains("detections"));
    EXPECT_TRUE(frame.contains("mask_coverage"));
    EXPECT_GT(frame["times_ms"]["segmentation"].get<double>(), 0.0);  // the network ran on this frame
  }
  fs::remove_all(dir);
}

// --skip-bad-frames: a missing frame ends the run without the flag; with it
// the run goes on, warns naming the file and counts the frame in stats.json.
TEST(RunCommand, SkipBadFramesGoesOnPastAMissingFrame) {
  const fs::path binary(STILLSLAM_BINARY);
  if (!fs::exists(binary)) GTEST_SKIP() << "build the stillslam binary first (" << binary << ")";
  const fs::path dir = fs::temp_directory_path() / "stillslam_test_run_skip_bad_frames";
  fs::remove_all(dir);
  const sim::SequenceSummary seq = write_small_sequence(dir, 20, false);
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

// --preload: the frames decoded before the run give the same trajectory bit
// for bit; a bound smaller than the frames is refused naming the option.
TEST(RunCommand, PreloadGivesTheSameTrajectoryAndRefusesOverTheBound) {
  const fs::path binary(STILLSLAM_BINARY);
  if (!fs::exists(binary)) GTEST_SKIP() << "build the stillslam binary first (" << binary << ")";
  const fs::path dir = fs::temp_directory_path() / "stillslam_test_run_preload";
  fs::remove_all(dir);
  const sim::SequenceSummary seq = write_small_sequence(dir, 20, false);
  const std::string base = binary.string() + " run --config " + seq.settings.string() + " --input " +
                           (dir / "seq").string() + " --no-segmentation --deterministic --vocabulary none";
  auto run = [&](const std::string& name, const std::string& flags) {
    const std::string cmd = base + " " + flags + " --output " + (dir / name).string() + " > " +
                            (dir / (name + ".log")).string() + " 2>&1";
    return std::system(cmd.c_str());
  };
  ASSERT_EQ(run("plain", ""), 0) << read_text(dir / "plain.log");
  ASSERT_EQ(run("preloaded", "--preload"), 0) << read_text(dir / "preloaded.log");
  const std::string plain = read_text(dir / "plain" / "trajectory.txt");
  EXPECT_EQ(count_lines(dir / "plain" / "trajectory.txt"), 20u);
  EXPECT_EQ(read_text(dir / "preloaded" / "trajectory.txt"), plain);
  std::ifstream stats_file(dir / "preloaded" / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(stats_file);
  EXPECT_EQ(stats["summary"]["preload"]["frames"].get<std::size_t>(), 20u);
  // 400x300 RGB-D: colour 3 + gray 1 + depth 4 bytes a pixel.
  EXPECT_EQ(stats["summary"]["preload"]["bytes"].get<std::size_t>(), 20u * 400 * 300 * 8);
  std::ifstream plain_stats_file(dir / "plain" / "stats.json");
  EXPECT_FALSE(nlohmann::json::parse(plain_stats_file)["summary"].contains("preload"));

  EXPECT_NE(run("bounded", "--preload --preload-limit-mb 10"), 0);  // 20 frames take ~18.3 MB
  const std::string log = read_text(dir / "bounded.log");
  EXPECT_NE(log.find("preloading 20 frames needs about 19 MB, more than the limit of 10 MB"), std::string::npos)
      << log;
  EXPECT_NE(log.find("--preload-limit-mb"), std::string::npos) << log;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace stillslam
