// The ZED 2i presets (config/zed2i_*.yaml): rectified stereo with a 0.12 m
// baseline at 1280x720 and 672x376, and the low-texture ORB variant.
#include <gtest/gtest.h>

#include <filesystem>

#include "stillslam/settings/settings.h"

namespace stillslam {
namespace {

std::filesystem::path preset(const char* name) { return std::filesystem::path(STILLSLAM_SOURCE_DIR) / "config" / name; }

TEST(SettingsPresets, Zed2i) {
  struct Expected {
    const char* file;
    int width, height;
    double fx, fps;
    int features, ini_th, min_th;
  };
  for (const Expected& e : {Expected{"zed2i_720p.yaml", 1280, 720, 530.0, 15, 1500, 20, 7},
                            Expected{"zed2i_vga.yaml", 672, 376, 265.0, 30, 1000, 20, 7},
                            Expected{"zed2i_720p_low_texture.yaml", 1280, 720, 530.0, 15, 2000, 12, 5}}) {
    SCOPED_TRACE(e.file);
    const Settings s = load_settings(preset(e.file));
    ASSERT_TRUE(s.stereo.has_value());
    EXPECT_TRUE(s.stereo->rectified);
    EXPECT_FALSE(s.rgbd);
    EXPECT_EQ(s.camera.width, e.width);
    EXPECT_EQ(s.camera.height, e.height);
    EXPECT_DOUBLE_EQ(s.camera.fx, e.fx);
    EXPECT_DOUBLE_EQ(s.camera.cx, e.width / 2.0);
    EXPECT_TRUE(s.camera.distortion.empty());
    EXPECT_NEAR(s.stereo->baseline, 0.12, 1e-9);
    EXPECT_NEAR(s.close_depth(), 40 * 0.12, 1e-9);
    EXPECT_DOUBLE_EQ(s.fps, e.fps);
    EXPECT_EQ(s.orb.n_features, e.features);
    EXPECT_EQ(s.orb.ini_th_fast, e.ini_th);
    EXPECT_EQ(s.orb.min_th_fast, e.min_th);
    EXPECT_NO_THROW(s.orb.check());
    EXPECT_NO_THROW(s.tracking.check());
    EXPECT_TRUE(s.segmentation.enabled);
  }
}

}  // namespace
}  // namespace stillslam
