#pragma once
// Runs the built `stillslam` binary for command-line tests.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace stillslam::test {

struct CommandRun {
  int status = -1;   // as returned by pclose
  std::string out;   // stdout (and stderr when merged)
};

inline CommandRun run_stillslam(const std::string& args, bool merge_stderr) {
  const std::string cmd = std::string(STILLSLAM_BINARY) + " " + args + (merge_stderr ? " 2>&1" : " 2>/dev/null");
  CommandRun r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe)) r.out += buf.data();
  r.status = pclose(pipe);
  return r;
}

}  // namespace stillslam::test

#define REQUIRE_STILLSLAM_BINARY()                                                            \
  if (!std::filesystem::exists(STILLSLAM_BINARY)) {                                           \
    GTEST_SKIP() << STILLSLAM_BINARY << " is not built (build the stillslam target first)"; \
  }
