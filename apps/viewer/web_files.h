#pragma once
// The viewer's web page (apps/viewer/web/), embedded in the binary at build
// time (cmake/embed_files.cmake), so it is served from any working directory.
#include <span>
#include <string_view>

namespace stillslam::viewer {

struct WebFile {
  std::string_view path;          // "/index.html", "/vendor/three/three.module.min.js"
  std::string_view content_type;
  std::string_view data;
};

std::span<const WebFile> web_files();

// The file served for a request path ("/" is /index.html); null when none.
const WebFile* find_web_file(std::string_view path);

}  // namespace stillslam::viewer
