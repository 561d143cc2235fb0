#pragma once
// Viewer.* settings of the HTTP viewer (not written yet; its settings are
// bound already so files can carry them). ORB-SLAM3's own Viewer.* keys
// (KeyFrameSize, ViewpointX, ...) describe its Pangolin window and are
// ignored; these names do not clash with them.
#include <string>

namespace stillslam {

struct ViewerOptions {
  int port = 8080;               // Viewer.port: TCP port the viewer serves on
  std::string host = "127.0.0.1";  // Viewer.host: address it listens on (127.0.0.1: this machine only)
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

}  // namespace stillslam
