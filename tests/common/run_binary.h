#pragma once
// Runs a shell command with stdout and stderr captured apart, for tests that
// check which stream a message goes to.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <sys/wait.h>

namespace stillslam::test {

struct SplitRun {
  int exit_code = -1;  // -1 when the process did not exit normally
  std::string out, err;
};

// `command` runs under /bin/sh; its two streams go to files next to `scratch`.
inline SplitRun run_split(const std::string& command, const std::filesystem::path& scratch) {
  const std::filesystem::path out = scratch.string() + ".stdout", err = scratch.string() + ".stderr";
  const int status = std::system((command + " > '" + out.string() + "' 2> '" + err.string() + "'").c_str());
  auto read = [](const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  SplitRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read(out);
  r.err = read(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

}  // namespace stillslam::test
