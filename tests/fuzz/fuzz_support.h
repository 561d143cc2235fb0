#pragma once
// Shared by the libFuzzer targets: readers that take a path get the input in
// a file of a per-process temporary folder; a stillslam::Error is the reader
// refusing bad input (fine), anything else escapes to libFuzzer as a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "stillslam/core/error.h"

namespace stillslam::fuzz {

// A folder of its own for this process (removed at exit), so parallel fuzzers
// do not share files.
inline const std::filesystem::path& temp_folder() {
  static const struct Folder {
    std::filesystem::path path;
    Folder() {
      path = std::filesystem::temp_directory_path() / ("stillslam_fuzz_" + std::to_string(::getpid()));
      std::filesystem::create_directories(path);
    }
    ~Folder() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  } folder;
  return folder.path;
}

inline void write_file(const std::filesystem::path& path, std::string_view bytes) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// The input as a file named `name` in the temporary folder.
inline std::filesystem::path input_file(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const std::filesystem::path path = temp_folder() / name;
  write_file(path, std::string_view(reinterpret_cast<const char*>(data), size));
  return path;
}

// Runs a reader; its stillslam::Error is the expected answer to bad input.
template <typename F>
void expect_error_or_result(F&& read) {
  try {
    read();
  } catch (const Error&) {
  }
}

}  // namespace stillslam::fuzz
