// `stillslam eval` through the binary (skipped when it is not built): inputs
// that used to give wrong numbers with exit 0, option ranges, which stream
// carries what, and a folder name that is not UTF-8.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "common/run_binary.h"
#include "stillslam/io/trajectory.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

class EvalCommandChecks : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(STILLSLAM_BINARY)) GTEST_SKIP() << STILLSLAM_BINARY << " is not built";
    dir_ = fs::temp_directory_path() / ("stillslam_eval_command_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // A tilted loop and an estimate with a known wobble: its RPE is not zero,
    // and it changes when the quaternions are read in the wrong order.
    Trajectory gt(60), est(60);
    for (std::size_t i = 0; i < gt.size(); ++i) {
      const double a = 2 * M_PI * static_cast<double>(i) / 60.0;
      gt[i].timestamp = est[i].timestamp = 1341846313.5 + 0.1 * static_cast<double>(i);
      gt[i].T_world_cam.linear() = (Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(0.3 * std::sin(a), Eigen::Vector3d::UnitX()))
                                       .toRotationMatrix();
      gt[i].T_world_cam.translation() = Eigen::Vector3d(2 * std::cos(a), 2 * std::sin(a), 0.2 * std::sin(2 * a));
      est[i].T_world_cam.linear() =
          gt[i].T_world_cam.linear() * Eigen::AngleAxisd(0.01 * std::sin(3 * a), Eigen::Vector3d::UnitY());
      est[i].T_world_cam.translation() = gt[i].T_world_cam.translation() + Eigen::Vector3d(0.01 * std::cos(5 * a), 0, 0);
    }
    write_trajectory(dir_ / "gt.txt", gt);
    write_trajectory(dir_ / "est.txt", est);
  }
  void TearDown() override {
    std::error_code ec;
    if (!dir_.empty()) fs::remove_all(dir_, ec);
  }

  test::SplitRun eval(const std::string& args) const {
    return test::run_split(std::string(STILLSLAM_BINARY) + " eval " + args, dir_ / "run");
  }
  std::string gt_est(const fs::path& est) const {
    return "--gt '" + (dir_ / "gt.txt").string() + "' --est '" + est.string() + "'";
  }
  static nlohmann::json read_json(const fs::path& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
  }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }
  std::string read(const std::string& name) const {
    std::ifstream in(dir_ / name, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }

  fs::path dir_;
};

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST_F(EvalCommandChecks, CommaSeparatedTumIsNotReadAsEuroc) {
  std::string commas = read("est.txt");
  for (char& c : commas) {
    if (c == ' ') c = ',';
  }
  const fs::path csv = write("est_commas.txt", commas);
  // No header names the quaternion order: an error that names the flag, not EuRoC's w-first guess.
  const auto ambiguous = eval(gt_est(csv));
  EXPECT_EQ(ambiguous.exit_code, 1);
  EXPECT_TRUE(contains(ambiguous.err, csv.string() + ", line 1")) << ambiguous.err;
  EXPECT_TRUE(contains(ambiguous.err, "--est-format")) << ambiguous.err;
  EXPECT_EQ(ambiguous.out, "");

  // With the format given, the numbers equal those of the blank-separated file.
  ASSERT_EQ(eval(gt_est(dir_ / "est.txt") + " --json '" + (dir_ / "spaces.json").string() + "'").exit_code, 0);
  const auto given = eval(gt_est(csv) + " --est-format tum --json '" + (dir_ / "commas.json").string() + "'");
  ASSERT_EQ(given.exit_code, 0) << given.err;
  const auto spaces = read_json(dir_ / "spaces.json"), with_commas = read_json(dir_ / "commas.json");
  const double rpe = spaces.at("rpe_trans").at("rmse").get<double>();
  EXPECT_GT(rpe, 1e-3);
  EXPECT_EQ(with_commas.at("rpe_trans").at("rmse").get<double>(), rpe);
  EXPECT_EQ(with_commas.at("rpe_rot").at("rmse").get<double>(), spaces.at("rpe_rot").at("rmse").get<double>());
  EXPECT_EQ(with_commas.at("pairs").get<int>(), 60);
  // --format sets both files' format (a unit quaternion is one in any order: only a header or a flag can tell).
  const auto both = eval(gt_est(csv) + " --format tum --json '" + (dir_ / "both.json").string() + "'");
  ASSERT_EQ(both.exit_code, 0) << both.err;
  EXPECT_EQ(read_json(dir_ / "both.json").at("rpe_trans").at("rmse").get<double>(), rpe);
  EXPECT_EQ(read_json(dir_ / "both.json").at("inputs").at("est_format").get<std::string>(), "tum");
}

TEST_F(EvalCommandChecks, KittiRowsWithElevenNumbersFail) {
  std::string rows;
  for (int i = 0; i < 30; ++i) rows += "1 0 0 " + std::to_string(i) + " 0 1 0 0 0 0 1\n";
  const fs::path kitti = write("kitti11.txt", rows);
  const auto r = eval("--gt '" + kitti.string() + "' --est '" + kitti.string() + "'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(contains(r.err, kitti.string() + ", line 1: cannot tell the trajectory format: found 11 fields")) << r.err;
  EXPECT_FALSE(contains(r.out, "associated"));
}

TEST_F(EvalCommandChecks, NumericOptionsAreChecked) {
  struct Case {
    std::string args, message;
  };
  for (const Case& c : {Case{"--max-dt -1", "--max-dt is -1: must be in (0, 10]"},
                        Case{"--max-dt nan", "--max-dt is nan: must be in (0, 10]"},
                        Case{"--max-dt 0", "--max-dt is 0: must be in (0, 10]"},
                        Case{"--offset inf", "--offset is inf: must be in [-1e+10, 1e+10]"},
                        Case{"--rpe-delta 0", "--rpe-delta is 0: must be in (0, 1e+09]"},
                        Case{"--rpe-delta nan", "--rpe-delta is nan: must be in (0, 1e+09]"}}) {
    const auto r = eval(gt_est(dir_ / "est.txt") + " " + c.args);
    EXPECT_EQ(r.exit_code, 1) << c.args;
    EXPECT_TRUE(contains(r.err, c.message)) << c.args << ": " << r.err;
    EXPECT_EQ(r.out, "") << c.args;
  }
  const auto good = eval(gt_est(dir_ / "est.txt") + " --max-dt 0.05 --json '" + (dir_ / "ok.json").string() + "'");
  ASSERT_EQ(good.exit_code, 0) << good.err;
  EXPECT_EQ(read_json(dir_ / "ok.json").at("association").at("max_dt").get<double>(), 0.05);
}

TEST_F(EvalCommandChecks, RpeWithoutPairsIsAbsentNotZero) {
  const auto r = eval(gt_est(dir_ / "est.txt") + " --rpe-delta 1000 --json '" + (dir_ / "r.json").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;  // the APE is valid
  EXPECT_TRUE(contains(r.err, "RPE: no pose pair is 1000 frames apart")) << r.err;
  const auto row = r.out.find("rpe_trans [m]");
  ASSERT_NE(row, std::string::npos) << r.out;
  const std::string line = r.out.substr(row, r.out.find('\n', row) - row);
  EXPECT_TRUE(contains(line, "n/a")) << line;
  EXPECT_FALSE(contains(line, "0.0")) << line;  // never a perfect 0
  const auto j = read_json(dir_ / "r.json");
  EXPECT_TRUE(j.at("rpe_trans").at("rmse").is_null());
  EXPECT_TRUE(j.at("rpe_rot").at("std").is_null());
  EXPECT_EQ(j.at("rpe_trans").at("count").get<int>(), 0);
  EXPECT_GT(j.at("ape").at("rmse").get<double>(), 0.0);
}

TEST_F(EvalCommandChecks, LogsAndErrorsGoToStderrResultsToStdout) {
  const auto missing = eval(gt_est(dir_ / "no_such.txt"));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(missing.out, "");
  EXPECT_TRUE(contains(missing.err, (dir_ / "no_such.txt").string() + " does not exist")) << missing.err;

  const auto folder = eval(gt_est(dir_));
  EXPECT_EQ(folder.exit_code, 1);
  EXPECT_TRUE(contains(folder.err, "trajectory file " + dir_.string() + " is a folder, expected a file")) << folder.err;

  const auto bad_flag = eval(gt_est(dir_ / "est.txt") + " --no-such-flag");
  EXPECT_NE(bad_flag.exit_code, 0);
  EXPECT_EQ(bad_flag.out, "");
  EXPECT_TRUE(contains(bad_flag.err, "--no-such-flag")) << bad_flag.err;

  const auto ok = eval(gt_est(dir_ / "est.txt") + " --plot '" + (dir_ / "plot.svg").string() + "'");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(contains(ok.out, "ape [m]"));
  EXPECT_FALSE(contains(ok.out, "plots:")) << ok.out;  // spdlog::info
  EXPECT_TRUE(contains(ok.err, "plots: ")) << ok.err;
}

TEST_F(EvalCommandChecks, FolderNameThatIsNotUtf8) {
  const fs::path latin1 = dir_ / "caf\xe9";  // "café" in Latin-1: not valid UTF-8
  fs::create_directories(latin1);
  fs::copy_file(dir_ / "gt.txt", latin1 / "gt.txt");
  fs::copy_file(dir_ / "est.txt", latin1 / "est.txt");
  const auto r = eval("--gt '" + (latin1 / "gt.txt").string() + "' --est '" + (latin1 / "est.txt").string() +
                      "' --json '" + (latin1 / "r.json").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const auto j = read_json(latin1 / "r.json");
  EXPECT_EQ(j.at("pairs").get<int>(), 60);
  // The byte that is not UTF-8 is written as U+FFFD.
  EXPECT_EQ(j.at("inputs").at("gt").get<std::string>(), (dir_ / "caf\xEF\xBF\xBD" / "gt.txt").string());
}

}  // namespace
}  // namespace stillslam
