#pragma once
#include <filesystem>
#include <fstream>
#include <string>

#include "stillslam/core/error.h"

namespace stillslam {

// Opens `path` for writing (replacing it); an Error names the file when it
// cannot be created.
inline std::ofstream open_for_writing(const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw Error("cannot write " + path.string() + "; check that its folder exists and is writable");
  return out;
}

// Writes `text` to `path`, replacing it; an Error names the file when it fails.
inline void write_text_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.flush();
  if (!out) throw Error("cannot write " + path.string() + ": check that its folder exists and is writable");
}

}  // namespace stillslam
