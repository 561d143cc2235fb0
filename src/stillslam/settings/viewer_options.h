#pragma once
// Viewer.* settings of the HTTP viewer (`stillslam run --viewer`, apps/viewer/).
// ORB-SLAM3's own Viewer.* keys (KeyFrameSize, ViewpointX, ...) describe its
// Pangolin window and are ignored; these names do not clash with them.
#include <string>

namespace stillslam {

struct ViewerOptions {
  int port = 8080;                 // Viewer.port: TCP port the viewer serves on (0: any free port)
  std::string host = "127.0.0.1";  // Viewer.host: address it listens on (127.0.0.1: this machine only)
  double image_rate = 10;          // Viewer.image_rate: frames (JPEG + overlay) sent per second, at most
  double map_rate = 2;             // Viewer.map_rate: map updates sent per second, at most
  int jpeg_quality = 80;           // Viewer.jpeg_quality: of the frames sent
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

}  // namespace stillslam
