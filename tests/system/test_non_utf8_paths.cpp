// `stillslam run` whose dataset and output folders have a Latin-1 name (not
// UTF-8): the run finishes with exit 0 and a stats.json that parses, the path
// written with U+FFFD where the byte is not UTF-8.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "common/run_binary.h"
#include "stillslam/sim/sequence_writer.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

TEST(RunCommand, FolderNameThatIsNotUtf8) {
  const fs::path binary(STILLSLAM_BINARY);
  if (!fs::exists(binary)) GTEST_SKIP() << "build the stillslam binary first (" << binary << ")";
  const fs::path dir = fs::temp_directory_path() / ("stillslam_test_non_utf8_" + std::to_string(::getpid())) / "caf\xe9";
  fs::remove_all(dir.parent_path());
  sim::SimulationOptions opts;
  opts.trajectory = "walking_xyz";
  opts.frames = 8;
  opts.width = 320;
  opts.height = 240;
  opts.no_people = true;
  opts.supersampling = 1;
  opts.data_dir = fs::path(STILLSLAM_SOURCE_DIR) / "data";
  const sim::SequenceSummary seq = sim::write_sequence(dir / "seq", opts);
  const fs::path out = dir / "out";
  const auto r = test::run_split(binary.string() + " run --config '" + seq.settings.string() + "' --input '" +
                                     (dir / "seq").string() + "' --output '" + out.string() +
                                     "' --no-segmentation --deterministic --vocabulary none",
                                 dir.parent_path() / "run");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(r.err.find("unexpected error") != std::string::npos) << r.err;
  ASSERT_GT(fs::file_size(out / "stats.json"), 0u);
  std::ifstream in(out / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(in);
  EXPECT_EQ(stats.at("input").get<std::string>(), (dir.parent_path() / "caf\xEF\xBF\xBD" / "seq").string());
  EXPECT_EQ(stats.at("frames").size(), 8u);
  fs::remove_all(dir.parent_path());
}

}  // namespace
}  // namespace stillslam
