// How `stillslam run` ends, through the binary on a small rendered sequence:
// exit codes (0 finished, 1 error, 128+N signal N), the "end" marker in
// stats.json, complete outputs after SIGINT/SIGTERM/SIGHUP/SIGQUIT (also with
// a second signal, and with a signal pending before the first instruction), a
// live trajectory that always reads back after SIGKILL, a full disk
// (RLIMIT_FSIZE), a reused output folder, and --save-map given a folder.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>
#include <string>
#include <thread>
#include <vector>
#include <nlohmann/json.hpp>

#include "common/child_process.h"
#include "io/temp_dir.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/settings/settings.h"
#include "stillslam/sim/sequence_writer.h"
#include "stillslam/system/system.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;
using test::ChildOptions;
using test::ChildProcess;
using test::describe_status;

constexpr int kFrames = 60;

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::size_t count_newlines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

nlohmann::json read_json(const fs::path& p) { return nlohmann::json::parse(read_text(p)); }

fs::path vocabulary_file() { return fs::path(STILLSLAM_SOURCE_DIR) / "vocab" / "orb_vocabulary.bin"; }

// Files in `dir` whose names show a write that did not finish.
std::vector<std::string> leftovers(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.find(".tmp-") != std::string::npos || name.find(".partial") != std::string::npos) found.push_back(name);
  }
  return found;
}

// Waits (no timing assertion) until `file` holds at least `lines` whole
// lines; false when the child exited first.
bool wait_for_lines(ChildProcess& child, const fs::path& file, std::size_t lines) {
  while (count_newlines(read_text(file)) < lines) {
    if (child.exited()) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

// Waits until `signal` is no longer pending for the child (its
// /proc/PID/status ShdPnd mask), i.e. it has taken it, or it has exited.
void wait_until_taken(ChildProcess& child, int signal) {
  const unsigned long long bit = 1ULL << (signal - 1);
  while (!child.exited()) {
    std::ifstream status("/proc/" + std::to_string(child.pid()) + "/status");
    std::string line;
    unsigned long long pending = 0;
    while (std::getline(status, line)) {
      if (line.rfind("ShdPnd:", 0) == 0) pending = std::stoull(line.substr(7), nullptr, 16);
    }
    if ((pending & bit) == 0) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

class RunOutputs : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(fs::temp_directory_path() / ("stillslam_run_outputs_" + std::to_string(::getpid())));
    fs::remove_all(*root_);
    sim::SimulationOptions opts;
    opts.trajectory = "walking_xyz";
    opts.frames = kFrames;
    opts.width = 320;
    opts.height = 240;
    opts.no_people = true;
    opts.supersampling = 1;
    opts.data_dir = fs::path(STILLSLAM_SOURCE_DIR) / "data";
    settings_ = new fs::path(sim::write_sequence(*root_ / "seq", opts).settings);
  }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete root_;
    delete settings_;
  }
  void SetUp() override {
    if (!fs::exists(STILLSLAM_BINARY)) GTEST_SKIP() << STILLSLAM_BINARY << " is not built";
  }

  static std::vector<std::string> run_args(const fs::path& out, std::vector<std::string> extra = {}) {
    std::vector<std::string> args{"run",      "--config", settings_->string(), "--input", (*root_ / "seq").string(),
                                  "--output", out.string(), "--no-segmentation", "--deterministic", "--vocabulary"};
    args.push_back(fs::exists(vocabulary_file()) ? vocabulary_file().string() : "none");
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }

  // trajectory.txt, keyframes.txt, trajectory_maps.txt and stats.json are
  // complete and agree with each other; returns stats.json.
  static nlohmann::json expect_complete_outputs(const fs::path& out) {
    const nlohmann::json stats = read_json(out / "stats.json");
    const std::size_t tracked = stats["summary"]["tracked"].get<std::size_t>();
    EXPECT_EQ(stats["frames"].size(), stats["end"]["frames_processed"].get<std::size_t>());
    EXPECT_EQ(stats["end"]["frames_in_input"].get<std::size_t>(), static_cast<std::size_t>(kFrames));
    const std::string trajectory = read_text(out / "trajectory.txt");
    EXPECT_EQ(count_newlines(trajectory), tracked);
    if (tracked > 0) {
      EXPECT_EQ(read_trajectory(out / "trajectory.txt").size(), tracked);
    }
    EXPECT_EQ(count_newlines(read_text(out / "trajectory_maps.txt")), tracked + 1);  // + the header
    const std::string keyframes = read_text(out / "keyframes.txt");
    EXPECT_EQ(count_newlines(keyframes), stats["summary"]["keyframes_in_map"].get<std::size_t>());
    EXPECT_TRUE(keyframes.empty() || keyframes.back() == '\n');
    EXPECT_EQ(leftovers(out), std::vector<std::string>{});
    return stats;
  }

  static fs::path* root_;
  static fs::path* settings_;
};
fs::path* RunOutputs::root_ = nullptr;
fs::path* RunOutputs::settings_ = nullptr;

TEST_F(RunOutputs, FinishedRunExitsZeroAndAReusedFolderNeedsForce) {
  test::TempDir dir;
  const fs::path out = dir.path() / "out";
  ChildProcess first(run_args(out));
  const int status = first.wait();
  ASSERT_EQ(describe_status(status), "exit 0") << first.output();
  const nlohmann::json stats = expect_complete_outputs(out);
  EXPECT_EQ(stats["end"]["reason"], "finished");
  EXPECT_TRUE(stats["end"]["signal"].is_null());
  EXPECT_EQ(stats["end"]["frames_processed"].get<int>(), kFrames);
  EXPECT_EQ(count_newlines(read_text(out / "trajectory_live.txt")), stats["summary"]["tracked"].get<std::size_t>());

  // The same folder again: refused before anything runs, the outputs untouched.
  const std::string stats_text = read_text(out / "stats.json");
  std::ofstream(out / "notes.md") << "mine\n";
  std::ofstream(out / "trajectory_old.txt") << "1 0 0 0 0 0 0 1\n";
  fs::create_directories(out / "trajectory_plots.txt");  // a folder: never removed
  ChildProcess again(run_args(out));
  EXPECT_EQ(describe_status(again.wait()), "exit 1") << again.output();
  EXPECT_NE(again.output().find("output folder " + out.string() +
                                " holds the outputs of an earlier run (keyframes.txt, stats.json, trajectory.txt, "
                                "trajectory_live.txt, trajectory_maps.txt, trajectory_old.txt); choose another "
                                "folder or pass --force to replace them"),
            std::string::npos)
      << again.output();
  EXPECT_EQ(read_text(out / "stats.json"), stats_text);

  // --force removes exactly those files; --max-frames ends as "max_frames", exit 0.
  ChildProcess forced(run_args(out, {"--force", "--max-frames", "5"}));
  ASSERT_EQ(describe_status(forced.wait()), "exit 0") << forced.output();
  const nlohmann::json short_stats = expect_complete_outputs(out);
  EXPECT_EQ(short_stats["end"]["reason"], "max_frames");
  EXPECT_EQ(short_stats["end"]["frames_processed"].get<int>(), 5);
  EXPECT_FALSE(fs::exists(out / "trajectory_old.txt"));
  EXPECT_EQ(read_text(out / "notes.md"), "mine\n");
  EXPECT_TRUE(fs::is_directory(out / "trajectory_plots.txt"));
}

// The bar: every handled signal ends the run with its exit code, complete
// outputs marked "interrupted" with the signal's name, and a map that loads.
TEST_F(RunOutputs, EachHandledSignalWritesCompleteOutputsAndALoadableMap) {
  if (!fs::exists(vocabulary_file())) GTEST_SKIP() << "no " << vocabulary_file();
  const Settings settings = load_settings(*settings_);
  for (const auto& [signal, name] : std::vector<std::pair<int, std::string>>{
           {SIGINT, "SIGINT"}, {SIGTERM, "SIGTERM"}, {SIGHUP, "SIGHUP"}, {SIGQUIT, "SIGQUIT"}}) {
    SCOPED_TRACE(name);
    test::TempDir dir;
    const fs::path out = dir.path() / "out";
    const fs::path map = dir.path() / "room.map";
    ChildProcess child(run_args(out, {"--save-map", map.string()}));
    ASSERT_TRUE(wait_for_lines(child, out / "trajectory_live.txt", 8)) << child.output();
    child.send(signal);
    EXPECT_EQ(describe_status(child.wait()), "exit " + std::to_string(128 + signal)) << child.output();
    const nlohmann::json stats = expect_complete_outputs(out);
    EXPECT_EQ(stats["end"]["reason"], "interrupted");
    EXPECT_EQ(stats["end"]["signal"], name);
    EXPECT_LT(stats["end"]["frames_processed"].get<int>(), kFrames);
    EXPECT_GE(stats["end"]["frames_processed"].get<int>(), 8);
    EXPECT_NE(child.output().find("stopped by " + name + " after"), std::string::npos) << child.output();
    ASSERT_TRUE(stats.contains("map_file")) << stats.dump();
    SystemOptions options;
    options.deterministic = true;
    options.vocabulary_path = vocabulary_file();
    options.load_map = map;
    System loaded(settings, SensorType::Rgbd, std::nullopt, options);
    EXPECT_EQ(loaded.keyframe_trajectory().size(), stats["map_file"]["keyframes"].get<std::size_t>());
    EXPECT_GE(loaded.keyframe_trajectory().size(), 1u);
    EXPECT_EQ(leftovers(dir.path()), std::vector<std::string>{});
  }
}

// A second signal while the first is handled (the outputs being written)
// neither kills the process nor cuts a file; the first one sets the code.
TEST_F(RunOutputs, ASecondSignalDoesNotCutTheOutputs) {
  test::TempDir dir;
  const fs::path out = dir.path() / "out";
  ChildProcess child(run_args(out));
  ASSERT_TRUE(wait_for_lines(child, out / "trajectory_live.txt", 8)) << child.output();
  child.send(SIGTERM);
  // Pending signals are taken lowest number first: the next ones are sent
  // once SIGTERM has been taken.
  wait_until_taken(child, SIGTERM);
  child.send(SIGINT);
  child.send(SIGHUP);
  EXPECT_EQ(describe_status(child.wait()), "exit 143") << child.output();
  const nlohmann::json stats = expect_complete_outputs(out);
  EXPECT_EQ(stats["end"]["signal"], "SIGTERM");
}

// A closed terminal window or ssh session: the kernel sends SIGHUP, and
// every later write to the terminal fails. Exit 129, complete outputs.
TEST_F(RunOutputs, AClosedTerminalEndsTheRunWithCompleteOutputs) {
  test::TempDir dir;
  const fs::path out = dir.path() / "out";
  ChildOptions options;
  options.terminal = true;
  ChildProcess child(run_args(out), options);
  ASSERT_TRUE(wait_for_lines(child, out / "trajectory_live.txt", 8)) << child.output();
  child.hang_up();
  EXPECT_EQ(describe_status(child.wait()), "exit 129") << child.output();
  const nlohmann::json stats = expect_complete_outputs(out);
  EXPECT_EQ(stats["end"]["reason"], "interrupted");
  EXPECT_EQ(stats["end"]["signal"], "SIGHUP");
  EXPECT_LT(stats["end"]["frames_processed"].get<int>(), kFrames);
}

// A signal already pending when the process starts (it arrived before any
// code ran) is taken first thing: no frame runs, and every output is written,
// empty but complete, with the end marker. The warning comes before anything
// else the command logs.
TEST_F(RunOutputs, ASignalBeforeTheFirstFrameWritesEmptyCompleteOutputs) {
  test::TempDir dir;
  const fs::path out = dir.path() / "out";
  ChildOptions options;
  options.pending_signal = SIGINT;
  ChildProcess child(run_args(out), options);
  EXPECT_EQ(describe_status(child.wait()), "exit 130") << child.output();
  const nlohmann::json stats = expect_complete_outputs(out);
  EXPECT_EQ(stats["end"]["reason"], "interrupted");
  EXPECT_EQ(stats["end"]["signal"], "SIGINT");
  EXPECT_EQ(stats["end"]["frames_processed"].get<int>(), 0);
  EXPECT_EQ(fs::file_size(out / "trajectory.txt"), 0u);
  EXPECT_EQ(fs::file_size(out / "trajectory_live.txt"), 0u);
  const std::string log = child.output();
  const auto warning = log.find("SIGINT: stopping before the next frame and writing all outputs");
  ASSERT_NE(warning, std::string::npos) << log;
  EXPECT_LT(warning, log.find("run: ")) << log;
}

// The bar: SIGKILL at 20 random moments (fixed seed). The live trajectory is
// always empty or whole lines that read back with the trajectory reader. Half
// of the kills come at a random time from the start, half a random time after
// the first pose.
TEST_F(RunOutputs, SigkillAtRandomMomentsLeavesAReadableLiveTrajectory) {
  test::TempDir dir;
  std::mt19937 random(15);
  std::uniform_int_distribution<int> delay_ms(0, 250);
  std::size_t with_poses = 0;
  for (int i = 0; i < 20; ++i) {
    SCOPED_TRACE("kill " + std::to_string(i));
    const fs::path out = dir.path() / ("out" + std::to_string(i));
    ChildProcess child(run_args(out));
    if (i % 2 == 1) {
      ASSERT_TRUE(wait_for_lines(child, out / "trajectory_live.txt", 1)) << child.output();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(random)));
    child.send(SIGKILL);
    child.wait();
    const fs::path live = out / "trajectory_live.txt";
    if (!fs::exists(live) || fs::file_size(live) == 0) continue;
    const std::string text = read_text(live);
    EXPECT_EQ(text.back(), '\n');
    EXPECT_EQ(read_trajectory(live).size(), count_newlines(text));
    ++with_poses;
  }
  EXPECT_GE(with_poses, 10u);  // at least every kill after the first pose
  std::cout << with_poses << " of 20 killed runs had written poses\n";
}

// A usage error is an error like any other: exit 1 (not CLI11's 1xx codes).
TEST_F(RunOutputs, UsageErrorsExitOne) {
  ChildProcess missing_input({"run", "--config", settings_->string(), "--output", "x"});
  EXPECT_EQ(describe_status(missing_input.wait()), "exit 1") << missing_input.output();
  EXPECT_NE(missing_input.output().find("--input is required"), std::string::npos) << missing_input.output();
  ChildProcess help({"run", "--help"});
  EXPECT_EQ(describe_status(help.wait()), "exit 0");
  EXPECT_NE(help.output().find("130 SIGINT (Ctrl-C), 143 SIGTERM, 129 SIGHUP"), std::string::npos) << help.output();
}

TEST_F(RunOutputs, SaveMapToAFolderIsRefusedBeforeTheRun) {
  test::TempDir dir;
  const fs::path out = dir.path() / "out";
  fs::create_directories(dir.path() / "maps");
  ChildProcess child(run_args(out, {"--save-map", (dir.path() / "maps").string()}));
  EXPECT_EQ(describe_status(child.wait()), "exit 1") << child.output();
  EXPECT_NE(child.output().find("--save-map " + (dir.path() / "maps").string() +
                                " is a folder; give the map file's path"),
            std::string::npos)
      << child.output();
  EXPECT_FALSE(fs::exists(out));  // nothing ran
  EXPECT_TRUE(fs::is_empty(dir.path() / "maps"));

  ChildProcess missing(run_args(out, {"--save-map", (dir.path() / "no" / "room.map").string()}));
  EXPECT_EQ(describe_status(missing.wait()), "exit 1") << missing.output();
  EXPECT_NE(missing.output().find("folder " + (dir.path() / "no").string() + " does not exist"), std::string::npos)
      << missing.output();
  EXPECT_FALSE(fs::exists(out));
}

// A full disk (RLIMIT_FSIZE: 16 kB per file): the trajectories fit, stats.json
// and the map do not. Exit 1, each failure named with its cause, the files
// that fit are complete, nothing half-written or temporary is left.
TEST_F(RunOutputs, AFullDiskKeepsWhatFitsAndNamesWhatDidNot) {
  test::TempDir dir;
  const fs::path out = dir.path() / "out";
  const fs::path map = out / "room.map";
  ChildOptions options;
  options.file_size_limit = 16384;
  ChildProcess child(run_args(out, {"--save-map", map.string()}), options);
  EXPECT_EQ(describe_status(child.wait()), "exit 1") << child.output();
  const std::string log = child.output();
  EXPECT_NE(log.find("cannot write " + (out / "stats.json").string() + ": File too large"), std::string::npos) << log;
  EXPECT_NE(log.find("cannot write map file " + map.string() + ": File too large"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(out / "stats.json"));
  EXPECT_FALSE(fs::exists(map));
  const std::size_t live = count_newlines(read_text(out / "trajectory_live.txt"));
  EXPECT_GE(live, 50u);
  EXPECT_EQ(read_trajectory(out / "trajectory.txt").size(), live);
  EXPECT_EQ(count_newlines(read_text(out / "trajectory_maps.txt")), live + 1);
  EXPECT_EQ(leftovers(out), std::vector<std::string>{});
}

// One output that cannot be written (a folder named trajectory.txt) does not
// stop the others: they are written, stats.json lists the failure, exit 1.
TEST_F(RunOutputs, OneUnwritableOutputDoesNotStopTheOthers) {
  test::TempDir dir;
  const fs::path out = dir.path() / "out";
  fs::create_directories(out / "trajectory.txt");
  ChildProcess child(run_args(out, {"--max-frames", "10"}));
  EXPECT_EQ(describe_status(child.wait()), "exit 1") << child.output();
  const std::string error = "cannot write trajectory file " + (out / "trajectory.txt").string() + ": Is a directory";
  EXPECT_NE(child.output().find(error), std::string::npos) << child.output();
  const nlohmann::json stats = read_json(out / "stats.json");
  EXPECT_EQ(stats["output_errors"], nlohmann::json::array({error}));
  EXPECT_EQ(stats["end"]["reason"], "max_frames");
  EXPECT_EQ(count_newlines(read_text(out / "trajectory_maps.txt")), stats["summary"]["tracked"].get<std::size_t>() + 1);
  EXPECT_TRUE(fs::exists(out / "keyframes.txt"));
  EXPECT_TRUE(fs::is_empty(out / "trajectory.txt"));
  EXPECT_EQ(leftovers(out), std::vector<std::string>{});
}

// The live file hits the limit (1500 bytes) mid-line: it is cut back to its
// last whole line at once, with one warning naming it and the cause.
TEST_F(RunOutputs, AFullDiskStopsTheLiveFileAtAWholeLineWithOneWarning) {
  test::TempDir dir;
  const fs::path out = dir.path() / "out";
  ChildOptions options;
  options.file_size_limit = 1500;
  ChildProcess child(run_args(out, {"--max-frames", "20"}), options);
  EXPECT_EQ(describe_status(child.wait()), "exit 1") << child.output();
  const std::string log = child.output();
  const std::string warning =
      "writing trajectory file " + (out / "trajectory_live.txt").string() + " failed (File too large)";
  const auto first = log.find(warning);
  ASSERT_NE(first, std::string::npos) << log;
  EXPECT_EQ(log.find(warning, first + 1), std::string::npos) << log;
  const std::string text = read_text(out / "trajectory_live.txt");
  EXPECT_LE(text.size(), 1500u);
  EXPECT_GT(text.size(), 1000u);  // every line is under 500 bytes
  EXPECT_EQ(text.back(), '\n');
  EXPECT_EQ(read_trajectory(out / "trajectory_live.txt").size(), count_newlines(text));
  const std::string trajectory_error =
      "cannot write trajectory file " + (out / "trajectory.txt").string() + ": File too large";
  EXPECT_NE(log.find(trajectory_error), std::string::npos) << log;
  EXPECT_EQ(leftovers(out), std::vector<std::string>{});
}

}  // namespace
}  // namespace stillslam
