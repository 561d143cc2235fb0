#pragma once
// What the settings tests share: a valid RGB-D settings file (segmentation
// off) to append keys to, and the Error message a settings file gives.
#include <filesystem>
#include <optional>
#include <string>

#include "io/temp_dir.h"
#include "stillslam/core/error.h"
#include "stillslam/settings/settings.h"

namespace stillslam::test {

inline const std::string kRgbdSettings = R"(%YAML:1.0
Camera.fx: 535.4
Camera.fy: 539.2
Camera.cx: 320.1
Camera.cy: 247.6
Camera.k1: 0.0
Camera.k2: 0.0
Camera.p1: 0.0
Camera.p2: 0.0
Camera.width: 640
Camera.height: 480
Camera.fps: 30.0
Camera.bf: 40.0
ThDepth: 40.0
DepthMapFactor: 5000.0
Segmentation.enabled: 0
)";

// Writes `text` into `dir`, loads it (as if by `executable` when given) and
// returns the Error message; "" when it loaded.
inline std::string settings_error(const TempDir& dir, const std::string& text,
                                  const std::optional<std::filesystem::path>& executable = std::nullopt) {
  const std::filesystem::path file = dir.write("bad.yaml", text);
  try {
    if (executable) {
      load_settings(file, *executable);
    } else {
      load_settings(file);
    }
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace stillslam::test
