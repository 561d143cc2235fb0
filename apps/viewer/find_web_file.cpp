#include "viewer/web_files.h"

namespace stillslam::viewer {

const WebFile* find_web_file(std::string_view path) {
  if (path == "/") path = "/index.html";
  for (const WebFile& f : web_files()) {
    if (f.path == path) return &f;
  }
  return nullptr;
}

}  // namespace stillslam::viewer
