// write_file_atomically: the target is replaced only by complete content, a
// failure names the file and the system's reason, no temporary file remains.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "stillslam/core/atomic_file.h"
#include "stillslam/core/text_file.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

class AtomicFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("stillslam_atomic_file_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  static std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }

  fs::path dir_;
};

TEST_F(AtomicFile, WritesAndReplacesWithoutLeavingTemporaryFiles) {
  const fs::path file = dir_ / "stats.json";
  write_file_atomically(file, "first\n");
  EXPECT_EQ(read(file), "first\n");
  write_text_file(file, "second, longer\n");
  EXPECT_EQ(read(file), "second, longer\n");
  write_file_atomically(file, "");
  EXPECT_TRUE(fs::exists(file));
  EXPECT_EQ(fs::file_size(file), 0u);
  EXPECT_EQ(entries(), std::vector<std::string>{"stats.json"});
}

TEST_F(AtomicFile, AFolderAsTargetIsAnErrorNamingItAndNothingIsLeft) {
  fs::create_directories(dir_ / "maps");
  try {
    write_file_atomically(dir_ / "maps", "payload");
    FAIL() << "writing over a folder must fail";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("cannot write " + (dir_ / "maps").string() + ": Is a directory"), std::string::npos) << what;
  }
  EXPECT_EQ(entries(), std::vector<std::string>{"maps"});
  EXPECT_TRUE(fs::is_empty(dir_ / "maps"));
}

TEST_F(AtomicFile, AMissingFolderIsAnErrorNamingTheFileAndWhatItIs) {
  try {
    write_file_atomically(dir_ / "missing" / "a.txt", "x", "map file");
    FAIL() << "a missing folder must fail";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write map file " + (dir_ / "missing" / "a.txt").string() +
                                         ": No such file or directory; check that its folder exists and is writable");
  }
}

// A full disk without root: in a child process, RLIMIT_FSIZE (with SIGXFSZ
// ignored) makes write() fail with EFBIG past 1000 bytes. The old content
// stays, the error names the file and the cause, the temporary file is gone.
TEST_F(AtomicFile, AFullDiskKeepsTheOldFileAndNamesTheCause) {
  const fs::path file = dir_ / "trajectory.txt";
  write_file_atomically(file, "old content\n");
  const fs::path message = dir_ / "message.txt";
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{1000, 1000};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    int code = 0;
    std::string what = "no error";
    try {
      write_file_atomically(file, std::string(5000, 'x'));
    } catch (const Error& e) {
      what = e.what();
      code = 3;
    }
    std::ofstream(message) << what.substr(0, 900);
    std::_Exit(code);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 3) << read(message);
  EXPECT_EQ(read(message), "cannot write " + file.string() + ": File too large");
  EXPECT_EQ(read(file), "old content\n");
  EXPECT_EQ(entries(), (std::vector<std::string>{"message.txt", "trajectory.txt"}));
}

}  // namespace
}  // namespace stillslam
