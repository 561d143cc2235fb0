#pragma once
#include <filesystem>
#include <fstream>
#include <string>

#include "stillslam/core/atomic_file.h"
#include "stillslam/core/error.h"

namespace stillslam {

// Opens `path` for writing (replacing it); an Error names the file when it
// cannot be created.
inline std::ofstream open_for_writing(const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw Error("cannot write " + path.string() + "; check that its folder exists and is writable");
  return out;
}

// Writes `text` to `path`, replacing it only once all of it is written
// (core/atomic_file.h); an Error names the file and the cause when it fails.
inline void write_text_file(const std::filesystem::path& path, const std::string& text) {
  write_file_atomically(path, text);
}

}  // namespace stillslam
