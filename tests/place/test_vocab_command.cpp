// `stillslam vocab` end to end through the built binary (skipped when the
// stillslam target is not built).
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/run_stillslam.h"
#include "place_fixtures.h"
#include "stillslam/place/vocabulary.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

using test::CommandRun;

CommandRun run(const std::string& args) { return test::run_stillslam(args, true); }

nlohmann::json last_json(const std::string& out) {
  const auto brace = out.find('{');
  return brace == std::string::npos ? nlohmann::json{} : nlohmann::json::parse(out.substr(brace));
}

TEST(VocabCommand, TrainInfoAndQuery) {
  REQUIRE_STILLSLAM_BINARY()
  const fs::path dir = fs::temp_directory_path() / "stillslam_vocab_command_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "images");
  const auto images = test::scene_images(6, 320, 240);
  for (std::size_t i = 0; i < images.size(); ++i)
    cv::imwrite((dir / "images" / ("scene_" + std::to_string(i) + ".png")).string(), images[i]);
  cv::imwrite((dir / "query.png").string(), test::moved(images[4], 6, -4, 2));
  const fs::path out = dir / "voc.bin";

  CommandRun r = run("vocab train --images " + (dir / "images").string() + " --out " + out.string() +
                     " --k 6 --levels 3 --features 300 --seed 3");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto trained = last_json(r.out);
  EXPECT_EQ(trained["images"], 6);
  EXPECT_EQ(trained["k"], 6);
  EXPECT_EQ(trained["levels"], 3);
  const Vocabulary voc = Vocabulary::load(out);
  EXPECT_EQ(trained["words"], voc.size());
  EXPECT_EQ(voc.training_images(), 6u);

  r = run("vocab info " + out.string());
  ASSERT_EQ(r.status, 0) << r.out;
  const auto info = last_json(r.out);
  EXPECT_EQ(info["words"], voc.size());
  EXPECT_EQ(info["nodes"], voc.node_count());
  EXPECT_EQ(info["weighting"], "tf-idf");

  r = run("vocab query --vocab " + out.string() + " --database " + (dir / "images").string() + " --image " +
          (dir / "query.png").string() + " --top 2 --features 300");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto q = last_json(r.out);
  ASSERT_EQ(q["matches"].size(), 2u);
  EXPECT_NE(q["matches"][0]["image"].get<std::string>().find("scene_4.png"), std::string::npos) << r.out;
}

TEST(VocabCommand, RejectsOtherFormatsWithTheFileName) {
  REQUIRE_STILLSLAM_BINARY()
  const fs::path dir = fs::temp_directory_path() / "stillslam_vocab_command_test_bad";
  fs::create_directories(dir);
  const fs::path dbow = dir / "ORBvoc.txt";
  std::ofstream(dbow) << "10 6  0 0\n0 0 252 188 188 242 169 109 85 143 187 171 0.0\n";
  const CommandRun r = run("vocab info " + dbow.string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("DBoW2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(dbow.string()), std::string::npos) << r.out;
  const CommandRun missing = run("vocab train --images " + (dir / "nothing").string() + " --out " + (dir / "x.bin").string());
  EXPECT_NE(missing.status, 0);
  EXPECT_NE(missing.out.find("does not exist"), std::string::npos) << missing.out;
}

}  // namespace
}  // namespace stillslam
