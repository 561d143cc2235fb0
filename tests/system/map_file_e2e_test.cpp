// Save -> load -> localization-only run on a rendered sequence: the mapping
// run saves its map; a second System loads it and tracks frames starting in
// the middle of the sequence (not at the map origin) without changing the
// map. Every localized pose must be within 1 cm of the mapping run's.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "io/temp_dir.h"
#include "stillslam/sim/sequence_writer.h"
#include "stillslam/core/error.h"
#include "stillslam/system/system.h"
#include "system/sim_sequence.h"

namespace stillslam {
namespace {

constexpr std::size_t kFrames = 90;
constexpr std::size_t kLocalizationStart = 40;

std::filesystem::path vocabulary_file() {
  return std::filesystem::path(STILLSLAM_SOURCE_DIR) / "vocab" / "orb_vocabulary.bin";
}

SystemOptions options_with(const std::filesystem::path& vocabulary) {
  SystemOptions options;
  options.deterministic = true;
  options.vocabulary_path = vocabulary;
  return options;
}

class MapFileEndToEnd : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    sequence_ = new test::SimSequence(test::render_sim_sequence("walking_xyz", kFrames, 320, 240, false));
    sequence_->settings.tracking.init_min_keypoints = 300;
  }
  static void TearDownTestSuite() {
    delete sequence_;
    sequence_ = nullptr;
  }
  static test::SimSequence* sequence_;
};
test::SimSequence* MapFileEndToEnd::sequence_ = nullptr;

TEST_F(MapFileEndToEnd, LocalizationOnlyRunReproducesTheMappingRun) {
  if (!std::filesystem::exists(vocabulary_file())) GTEST_SKIP() << "no " << vocabulary_file();
  const test::SimSequence& seq = *sequence_;
  test::TempDir dir;
  const auto map_path = dir.path() / "room.map";

  // Mapping run, saved at the end.
  Trajectory mapped;
  MapFileStats saved;
  {
    System system(seq.settings, SensorType::Rgbd, seq.stereo, options_with(vocabulary_file()));
    for (const SensorFrame& f : seq.frames) system.process(f);
    saved = system.save_map(map_path);
    mapped = system.trajectory();
  }
  ASSERT_EQ(mapped.size(), kFrames);
  EXPECT_EQ(saved.maps, 1u);
  EXPECT_GE(saved.keyframes, 4u);
  EXPECT_GT(saved.map_points, 500u);
  std::cout << "saved " << saved.keyframes << " keyframes, " << saved.map_points << " points, " << saved.bytes
            << " bytes\n";

  // Localization only, from the middle of the sequence.
  SystemOptions options = options_with(vocabulary_file());
  options.load_map = map_path;
  options.localization_only = true;
  System localizer(seq.settings, SensorType::Rgbd, seq.stereo, options);
  EXPECT_EQ(localizer.num_keyframes(), saved.keyframes);
  EXPECT_EQ(localizer.num_map_points(), saved.map_points);
  std::vector<FrameStats> frames;
  for (std::size_t i = kLocalizationStart; i < kFrames; ++i) frames.push_back(localizer.process(seq.frames[i]));
  localizer.shutdown();

  // Relocalized at once (the frame is far from the origin keyframe), then tracked throughout.
  ASSERT_FALSE(frames.empty());
  EXPECT_EQ(frames.front().reason, "relocalized");
  for (const FrameStats& f : frames) {
    EXPECT_TRUE(f.has_pose) << "frame " << f.index << ": " << f.reason;
    EXPECT_FALSE(f.keyframe) << "frame " << f.index;
  }
  // The map is unchanged: no keyframes, no points, one map.
  EXPECT_EQ(localizer.num_keyframes(), saved.keyframes);
  EXPECT_EQ(localizer.num_map_points(), saved.map_points);
  EXPECT_EQ(localizer.num_maps(), 1u);
  EXPECT_EQ(localizer.mapper_stats().keyframes, 0);

  // The bar: every pose within 1 cm of the mapping run (same world frame, no alignment).
  std::map<double, Eigen::Vector3d> reference;
  for (const StampedPose& p : mapped) reference.emplace(p.timestamp, p.T_world_cam.translation());
  const Trajectory localized = localizer.trajectory();
  ASSERT_EQ(localized.size(), kFrames - kLocalizationStart);
  double max_difference = 0;
  for (const StampedPose& p : localized) {
    ASSERT_EQ(reference.count(p.timestamp), 1u);
    max_difference = std::max(max_difference, (p.T_world_cam.translation() - reference[p.timestamp]).norm());
  }
  std::cout << "localization vs mapping run: max position difference " << 100 * max_difference << " cm over "
            << localized.size() << " frames\n";
  EXPECT_LT(max_difference, 0.01);
}

TEST_F(MapFileEndToEnd, LoadingNeedsAMapAndTheVocabulary) {
  const test::SimSequence& seq = *sequence_;
  SystemOptions options;
  options.localization_only = true;
  try {
    System system(seq.settings, SensorType::Rgbd, seq.stereo, options);
    FAIL() << "localization without a map must be an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--load-map"), std::string::npos) << e.what();
  }
  test::TempDir dir;
  options.load_map = dir.write("room.map", "not a map");
  try {
    System system(seq.settings, SensorType::Rgbd, seq.stereo, options);
    FAIL() << "loading a map without a vocabulary must be an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("room.map: starting from a saved map needs the vocabulary"),
              std::string::npos)
        << e.what();
  }
  if (!std::filesystem::exists(vocabulary_file())) GTEST_SKIP() << "no " << vocabulary_file();
  options.vocabulary_path = vocabulary_file();
  try {
    System system(seq.settings, SensorType::Rgbd, seq.stereo, options);
    FAIL() << "a file that is not a map must be an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("room.map: not a stillslam map file"), std::string::npos) << e.what();
  }
  // A run that never initialized saves no map; loading it says so.
  {
    System never(seq.settings, SensorType::Rgbd, seq.stereo, options_with(vocabulary_file()));
    SensorFrame black = seq.frames[0];
    black.gray = cv::Mat::zeros(black.gray.size(), black.gray.type());
    black.color = cv::Mat::zeros(black.color.size(), black.color.type());
    never.process(black);
    EXPECT_EQ(never.save_map(dir.path() / "empty.map").maps, 0u);
  }
  options.load_map = dir.path() / "empty.map";
  try {
    System system(seq.settings, SensorType::Rgbd, seq.stereo, options);
    FAIL() << "a map file without keyframes must be an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("empty.map: the map file holds no keyframes"), std::string::npos)
        << e.what();
  }
}

// Through the binary: --save-map writes the map, --load-map --localization
// tracks the same frames against it without creating keyframes.
TEST(MapFileCommand, SaveThenLocalize) {
  namespace fs = std::filesystem;
  const fs::path binary(STILLSLAM_BINARY);
  if (!fs::exists(binary)) GTEST_SKIP() << "build the stillslam binary first (" << binary << ")";
  if (!fs::exists(vocabulary_file())) GTEST_SKIP() << "no " << vocabulary_file();
  test::TempDir dir;
  sim::SimulationOptions opts;
  opts.trajectory = "walking_xyz";
  opts.frames = 40;
  opts.width = 320;
  opts.height = 240;
  opts.no_people = true;
  opts.supersampling = 1;
  opts.data_dir = fs::path(STILLSLAM_SOURCE_DIR) / "data";
  const sim::SequenceSummary seq = sim::write_sequence(dir.path() / "seq", opts);
  const std::string common = binary.string() + " run --config " + seq.settings.string() + " --input " +
                             (dir.path() / "seq").string() + " --no-segmentation --deterministic --vocabulary " +
                             vocabulary_file().string();
  const fs::path map_file = dir.path() / "seq.map";
  const fs::path log = dir.path() / "log.txt";
  ASSERT_EQ(std::system((common + " --output " + (dir.path() / "mapping").string() + " --save-map " +
                         map_file.string() + " > " + log.string() + " 2>&1")
                            .c_str()),
            0)
      << "see " << log;
  ASSERT_TRUE(fs::exists(map_file));
  const nlohmann::json mapping = nlohmann::json::parse(std::ifstream(dir.path() / "mapping" / "stats.json"));
  EXPECT_EQ(mapping["map_file"]["bytes"].get<std::uint64_t>(), fs::file_size(map_file));
  const std::size_t keyframes = mapping["map_file"]["keyframes"].get<std::size_t>();
  EXPECT_GE(keyframes, 1u);

  ASSERT_EQ(std::system((common + " --output " + (dir.path() / "localization").string() + " --load-map " +
                         map_file.string() + " --localization > " + log.string() + " 2>&1")
                            .c_str()),
            0)
      << "see " << log;
  const nlohmann::json localization =
      nlohmann::json::parse(std::ifstream(dir.path() / "localization" / "stats.json"));
  EXPECT_TRUE(localization["localization_only"].get<bool>());
  EXPECT_EQ(localization["summary"]["tracked"].get<std::size_t>(), 40u);
  EXPECT_EQ(localization["summary"]["keyframes_in_map"].get<std::size_t>(), keyframes);
  EXPECT_EQ(localization["frames"][0]["reason"].get<std::string>(), "relocalized");

  // --localization without a map is refused by the command line.
  EXPECT_NE(std::system((common + " --output " + (dir.path() / "x").string() + " --localization > " +
                         log.string() + " 2>&1")
                            .c_str()),
            0);
}

}  // namespace
}  // namespace stillslam
