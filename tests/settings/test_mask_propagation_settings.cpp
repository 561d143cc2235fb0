// MaskPropagation.* keys: bound to MaskPropagationOptions, defaults kept when
// absent, a bad value is an error naming the key and its range.
#include <gtest/gtest.h>

#include <string>

#include "io/temp_dir.h"
#include "settings_test_files.h"
#include "stillslam/core/error.h"
#include "stillslam/settings/settings.h"

namespace stillslam {
namespace {

using test::TempDir;

const std::string& kBase = test::kRgbdSettings;

TEST(MaskPropagationSettings, KeysBindAndDefaultsStay) {
  TempDir dir;
  const Settings defaults = load_settings(dir.write("a.yaml", kBase));
  EXPECT_EQ(defaults.mask_propagation.mode, MaskPropagationOptions{}.mode);
  EXPECT_EQ(defaults.mask_propagation.lk_window_px, MaskPropagationOptions{}.lk_window_px);
  const Settings s = load_settings(dir.write(
      "b.yaml", kBase + "MaskPropagation.mode: 1\nMaskPropagation.marginPx: 6\nMaskPropagation.marginPxPerFrame: 2.5\n"
                        "MaskPropagation.maxMarginPx: 40\nMaskPropagation.pointsPerInstance: 80\n"
                        "MaskPropagation.lkWindowPx: 21\nMaskPropagation.lkLevels: 4\n"
                        "MaskPropagation.fbMaxErrorPx: 0\nMaskPropagation.maxDepth: 8\n"
                        "MaskPropagation.splitMinPx: 0\nMaskPropagation.stereoBlockDepth: 1\n"));
  EXPECT_EQ(s.mask_propagation.mode, 1);
  EXPECT_EQ(s.mask_propagation.margin_px, 6);
  EXPECT_DOUBLE_EQ(s.mask_propagation.margin_px_per_frame, 2.5);
  EXPECT_EQ(s.mask_propagation.max_margin_px, 40);
  EXPECT_EQ(s.mask_propagation.points_per_instance, 80);
  EXPECT_EQ(s.mask_propagation.lk_window_px, 21);
  EXPECT_EQ(s.mask_propagation.lk_levels, 4);
  EXPECT_DOUBLE_EQ(s.mask_propagation.fb_max_error_px, 0);
  EXPECT_DOUBLE_EQ(s.mask_propagation.max_depth_m, 8);
  EXPECT_EQ(defaults.mask_propagation.split_min_px, 400);
  EXPECT_EQ(s.mask_propagation.split_min_px, 0);
  EXPECT_FALSE(defaults.mask_propagation.stereo_block_depth);
  EXPECT_TRUE(s.mask_propagation.stereo_block_depth);
}

TEST(MaskPropagationSettings, BadValuesNameTheKey) {
  TempDir dir;
  EXPECT_NE(test::settings_error(dir, kBase + "MaskPropagation.mode: 3\n").find("MaskPropagation.mode' is 3: must be in [0, 2]"),
            std::string::npos);
  EXPECT_NE(test::settings_error(dir, kBase + "MaskPropagation.splitMinPx: -1\n").find("MaskPropagation.splitMinPx"),
            std::string::npos);
  EXPECT_NE(test::settings_error(dir, kBase + "MaskPropagation.lkWindowPx: 20\n").find("MaskPropagation.lkWindowPx"),
            std::string::npos);
  EXPECT_NE(test::settings_error(dir, kBase + "MaskPropagation.marginPx: 9\nMaskPropagation.maxMarginPx: 5\n")
                .find("MaskPropagation.maxMarginPx"),
            std::string::npos);
  EXPECT_NE(test::settings_error(dir, kBase + "MaskPropagation.stereoBlockDepth: 2\n").find("MaskPropagation.stereoBlockDepth"),
            std::string::npos);
  EXPECT_NE(test::settings_error(dir, kBase + "MaskPropagation.lkWindow: 21\n").find("known keys"), std::string::npos);
}

}  // namespace
}  // namespace stillslam
