// io/camera_settings: Camera.fps is bounded, so the keyframe spacing derived
// from it (one second of frames, an int) cannot overflow (fuzz_settings: 1e101
// was cast to int in settings/tracking_settings.cpp, a UBSan report).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "io/temp_dir.h"
#include "stillslam/core/error.h"
#include "stillslam/io/camera_settings.h"

namespace stillslam {
namespace {

std::string fps_error(const test::TempDir& dir, const std::string& fps) {
  std::ifstream in(std::string(STILLSLAM_SOURCE_DIR) + "/config/tum_fr1.yaml");
  std::stringstream text;
  text << in.rdbuf() << "\nCamera.fps: " << fps << "\n";
  std::string yaml = text.str();
  // The preset's own Camera.fps line goes; the appended one is the only one.
  const auto at = yaml.find("Camera.fps:");
  yaml.erase(at, yaml.find('\n', at) - at);
  try {
    load_camera_settings(dir.write("fps.yaml", yaml));
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(CameraSettings, FpsOutsideItsRangeIsAnError) {
  test::TempDir dir;
  for (const char* bad : {"1.0e101", "0", "-30", "1001"}) {
    const std::string message = fps_error(dir, bad);
    EXPECT_NE(message.find("fps.yaml: key 'Camera.fps' is "), std::string::npos) << bad << ": " << message;
    EXPECT_NE(message.find(": must be in [0.1, 1000] (frames per second)"), std::string::npos) << bad << ": " << message;
  }
  EXPECT_EQ(fps_error(dir, "1000"), "");
  EXPECT_EQ(fps_error(dir, "30.0"), "");
}

}  // namespace
}  // namespace stillslam
