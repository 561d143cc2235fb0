// Motion.* keys: bound to MotionOptions, off by default, a bad value is an
// error naming the key and its range.
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

TEST(MotionSettings, KeysBindAndDefaultsStay) {
  TempDir dir;
  const Settings defaults = load_settings(dir.write("a.yaml", kBase));
  EXPECT_FALSE(defaults.motion.enabled);
  EXPECT_EQ(defaults.motion.span, MotionOptions{}.span);
  const Settings s = load_settings(dir.write(
      "b.yaml", kBase + "Motion.enabled: 1\nMotion.instanceFeatures: 120\nMotion.span: 8\nMotion.personFrames: 20\n"
                        "Motion.defaultFrames: 5\nMotion.minIou: 0.4\n"));
  EXPECT_TRUE(s.motion.enabled);
  EXPECT_EQ(s.motion.instance_features, 120);
  EXPECT_EQ(s.motion.span, 8);
  EXPECT_EQ(s.motion.person_frames, 20);
  EXPECT_EQ(s.motion.default_frames, 5);
  EXPECT_DOUBLE_EQ(s.motion.min_iou, 0.4);
  EXPECT_EQ(s.motion.check_options().evidence.frames_for("person"), 20);
  EXPECT_EQ(s.motion.check_options().evidence.frames_for("chair"), 5);
}

// Objects' own moving bar, features of unmasked objects, places of instances
// that come back under a new id.
TEST(MotionSettings, ObjectAndPlaceKeysBind) {
  TempDir dir;
  const Settings defaults = load_settings(dir.write("a.yaml", kBase));
  EXPECT_TRUE(defaults.motion.watch_objects);
  EXPECT_DOUBLE_EQ(defaults.motion.place_radius_m, MotionOptions{}.place_radius_m);
  const Settings s = load_settings(dir.write(
      "b.yaml", kBase + "Motion.watchObjects: 0\nMotion.objectMovingFactor: 2.5\nMotion.objectMovingFloorPx: 2\n"
                        "Motion.placeRadius: 0.3\nMotion.placeMemoryFrames: 90\n"));
  EXPECT_FALSE(s.motion.watch_objects);
  EXPECT_DOUBLE_EQ(s.motion.check_options().evidence.object_moving_factor, 2.5);
  EXPECT_DOUBLE_EQ(s.motion.check_options().evidence.object_moving_floor_px, 2.0);
  EXPECT_DOUBLE_EQ(s.motion.places_options().radius_m, 0.3);
  EXPECT_EQ(s.motion.places_options().memory_frames, 90);
  // Below the agreeing bar (2x, 1.5 px) an object could agree and disagree at once.
  const std::string e = test::settings_error(dir, kBase + "Motion.objectMovingFactor: 1.5\n");
  EXPECT_NE(e.find("Motion.objectMovingFactor"), std::string::npos) << e;
  const std::string f = test::settings_error(dir, kBase + "Motion.objectMovingFloorPx: 1\n");
  EXPECT_NE(f.find("Motion.objectMovingFloorPx"), std::string::npos) << f;
  const std::string g = test::settings_error(dir, kBase + "Motion.placeRadius: -1\n");
  EXPECT_NE(g.find("Motion.placeRadius"), std::string::npos) << g;
}

// How long points on a person kept as static live.
TEST(MotionSettings, KeptPointFramesBinds) {
  TempDir dir;
  EXPECT_EQ(load_settings(dir.write("a.yaml", kBase)).motion.kept_point_frames, 30);
  EXPECT_EQ(load_settings(dir.write("b.yaml", kBase + "Motion.keptPointFrames: 0\n")).motion.kept_point_frames, 0);
  const std::string e = test::settings_error(dir, kBase + "Motion.keptPointFrames: -1\n");
  EXPECT_NE(e.find("Motion.keptPointFrames"), std::string::npos) << e;
}

TEST(MotionSettings, KeptPointsOutOfPoseBinds) {
  TempDir dir;
  EXPECT_FALSE(load_settings(dir.write("a.yaml", kBase)).motion.kept_points_out_of_pose);
  EXPECT_TRUE(
      load_settings(dir.write("b.yaml", kBase + "Motion.keptPointsOutOfPose: 1\n")).motion.kept_points_out_of_pose);
  const std::string e = test::settings_error(dir, kBase + "Motion.keptPointsOutOfPose: 2\n");
  EXPECT_NE(e.find("Motion.keptPointsOutOfPose"), std::string::npos) << e;
}

TEST(MotionSettings, KeptPointSigmaBinds) {
  TempDir dir;
  EXPECT_DOUBLE_EQ(load_settings(dir.write("a.yaml", kBase)).motion.kept_point_sigma, 1);
  EXPECT_DOUBLE_EQ(load_settings(dir.write("b.yaml", kBase + "Motion.keptPointSigma: 3\n")).motion.kept_point_sigma, 3);
  const std::string e = test::settings_error(dir, kBase + "Motion.keptPointSigma: 0.5\n");
  EXPECT_NE(e.find("Motion.keptPointSigma"), std::string::npos) << e;
}

TEST(MotionSettings, KeptFeaturesBinds) {
  TempDir dir;
  EXPECT_EQ(load_settings(dir.write("a.yaml", kBase)).motion.kept_features, 0);
  EXPECT_EQ(load_settings(dir.write("b.yaml", kBase + "Motion.keptFeatures: 100\n")).motion.kept_features, 100);
  const std::string e = test::settings_error(dir, kBase + "Motion.keptFeatures: -1\n");
  EXPECT_NE(e.find("Motion.keptFeatures"), std::string::npos) << e;
}

TEST(MotionSettings, KeptFeaturesAreaFactorBinds) {
  TempDir dir;
  EXPECT_DOUBLE_EQ(load_settings(dir.write("a.yaml", kBase)).motion.kept_features_area_factor, 0);
  EXPECT_DOUBLE_EQ(
      load_settings(dir.write("b.yaml", kBase + "Motion.keptFeaturesAreaFactor: 1.5\n")).motion.kept_features_area_factor,
      1.5);
  for (const std::string bad : {"Motion.keptFeaturesAreaFactor: -0.1\n", "Motion.keptFeaturesAreaFactor: 11\n"}) {
    const std::string e = test::settings_error(dir, kBase + bad);
    EXPECT_NE(e.find("Motion.keptFeaturesAreaFactor"), std::string::npos) << e;
  }
}

TEST(MotionSettings, PredictedCheckBinds) {
  TempDir dir;
  EXPECT_FALSE(load_settings(dir.write("a.yaml", kBase)).motion.predicted_check);
  EXPECT_TRUE(load_settings(dir.write("b.yaml", kBase + "Motion.predictedCheck: 1\n")).motion.predicted_check);
  const std::string e = test::settings_error(dir, kBase + "Motion.predictedCheck: 2\n");
  EXPECT_NE(e.find("Motion.predictedCheck"), std::string::npos) << e;
}

TEST(MotionSettings, KeptPointsOutOfBABinds) {
  TempDir dir;
  EXPECT_FALSE(load_settings(dir.write("a.yaml", kBase)).motion.kept_points_out_of_ba);
  EXPECT_TRUE(load_settings(dir.write("b.yaml", kBase + "Motion.keptPointsOutOfBA: 1\n")).motion.kept_points_out_of_ba);
  const std::string e = test::settings_error(dir, kBase + "Motion.keptPointsOutOfBA: 2\n");
  EXPECT_NE(e.find("Motion.keptPointsOutOfBA"), std::string::npos) << e;
}

TEST(MotionSettings, FreeSpaceShareBinds) {
  TempDir dir;
  EXPECT_DOUBLE_EQ(load_settings(dir.write("a.yaml", kBase)).motion.free_space_share, 0);
  EXPECT_DOUBLE_EQ(load_settings(dir.write("b.yaml", kBase + "Motion.freeSpaceShare: 0.3\n")).motion.free_space_share, 0.3);
  const std::string e = test::settings_error(dir, kBase + "Motion.freeSpaceShare: 1.5\n");
  EXPECT_NE(e.find("Motion.freeSpaceShare"), std::string::npos) << e;
}

TEST(MotionSettings, DepthCheckAndMatchWindowKeysBind) {
  TempDir dir;
  const Settings defaults = load_settings(dir.write("a.yaml", kBase));
  EXPECT_EQ(defaults.motion.free_space_frames, 0);
  EXPECT_EQ(defaults.motion.free_space_span(), defaults.motion.span);
  EXPECT_FALSE(defaults.motion.free_space.count_nearer);
  EXPECT_FALSE(defaults.motion.free_space_vacated);
  EXPECT_DOUBLE_EQ(defaults.motion.match_window_px, 0);
  EXPECT_DOUBLE_EQ(defaults.motion.check_options().window_px, 0);
  const Settings s = load_settings(dir.write(
      "b.yaml", kBase + "Motion.freeSpaceFrames: 18\nMotion.freeSpaceNearer: 1\nMotion.matchWindowPx: 96\n"
                        "Motion.freeSpaceVacated: 1\n"));
  EXPECT_TRUE(s.motion.free_space_vacated);
  EXPECT_EQ(s.motion.free_space_frames, 18);
  EXPECT_EQ(s.motion.free_space_span(), 18);
  EXPECT_TRUE(s.motion.free_space.count_nearer);
  EXPECT_DOUBLE_EQ(s.motion.match_window_px, 96);
  EXPECT_DOUBLE_EQ(s.motion.check_options().window_px, 96);
  // Range rows: each bad value names its key.
  for (const std::string bad : {"Motion.freeSpaceFrames: 101\n", "Motion.freeSpaceFrames: -1\n",
                                "Motion.freeSpaceNearer: 2\n", "Motion.freeSpaceVacated: 2\n", "Motion.matchWindowPx: -1\n",
                                "Motion.matchWindowPx: 10001\n"}) {
    const std::string e = test::settings_error(dir, kBase + bad);
    EXPECT_NE(e.find(bad.substr(0, bad.find(':'))), std::string::npos) << bad << ": " << e;
  }
}

TEST(MotionSettings, SparseViewKeysBind) {
  TempDir dir;
  const Settings defaults = load_settings(dir.write("a.yaml", kBase));
  EXPECT_FALSE(defaults.motion.sparse_view.enabled);
  EXPECT_DOUBLE_EQ(defaults.motion.sparse_view.masked_share, 0.5);
  EXPECT_EQ(defaults.motion.sparse_view.inliers, 100000);
  EXPECT_DOUBLE_EQ(defaults.motion.sparse_view.tracked_weight, 0.2);
  EXPECT_TRUE(defaults.motion.sparse_view.keyframes);
  EXPECT_FALSE(defaults.motion.sparse_view.prior);
  EXPECT_EQ(defaults.motion.sparse_view.smooth_frames, 0);
  EXPECT_DOUBLE_EQ(defaults.motion.sparse_view.filter_gain, 0.0);
  EXPECT_EQ(defaults.motion.sparse_view.filter_frames, 5);
  EXPECT_EQ(defaults.motion.sparse_view.filter_axes, 3);
  EXPECT_DOUBLE_EQ(defaults.motion.sparse_view.keyframe_prior_sigma, 0.0);
  const Settings s = load_settings(dir.write(
      "b.yaml", kBase + "Motion.sparseView: 1\nMotion.sparseViewMaskedShare: 0.6\nMotion.sparseViewInliers: 80\n"
                        "Motion.sparseViewTrackedWeight: 0.3\nMotion.sparseViewKeyframes: 0\n"
                        "Motion.sparseViewPrior: 1\nMotion.sparseViewSmoothFrames: 3\n"
                        "Motion.sparseViewFilterGain: 0.4\nMotion.sparseViewFilterFrames: 8\n"
                        "Motion.sparseViewFilterAxes: 1\nMotion.sparseViewKeyframePriorSigma: 0.002\n"));
  EXPECT_TRUE(s.motion.sparse_view.enabled);
  EXPECT_DOUBLE_EQ(s.motion.sparse_view.masked_share, 0.6);
  EXPECT_EQ(s.motion.sparse_view.inliers, 80);
  EXPECT_DOUBLE_EQ(s.motion.sparse_view.tracked_weight, 0.3);
  EXPECT_FALSE(s.motion.sparse_view.keyframes);
  EXPECT_TRUE(s.motion.sparse_view.prior);
  EXPECT_EQ(s.motion.sparse_view.smooth_frames, 3);
  EXPECT_DOUBLE_EQ(s.motion.sparse_view.filter_gain, 0.4);
  EXPECT_EQ(s.motion.sparse_view.filter_frames, 8);
  EXPECT_EQ(s.motion.sparse_view.filter_axes, 1);
  EXPECT_DOUBLE_EQ(s.motion.sparse_view.keyframe_prior_sigma, 0.002);
  for (const std::string bad : {"Motion.sparseViewFilterGain: -0.1\n", "Motion.sparseViewFilterGain: 1.5\n",
                                "Motion.sparseViewFilterFrames: 0\n", "Motion.sparseViewFilterFrames: 101\n",
                                "Motion.sparseViewTrackedWeight: 2\n", "Motion.sparseViewKeyframes: 2\n",
                                "Motion.sparseViewPrior: -1\n", "Motion.sparseViewSmoothFrames: -1\n",
                                "Motion.sparseViewSmoothFrames: 101\n", "Motion.sparseViewFilterAxes: 0\n",
                                "Motion.sparseViewFilterAxes: 4\n", "Motion.sparseViewKeyframePriorSigma: -0.001\n",
                                "Motion.sparseViewKeyframePriorSigma: 2\n"}) {
    const std::string e = test::settings_error(dir, kBase + bad);
    EXPECT_NE(e.find(bad.substr(0, bad.find(':'))), std::string::npos) << bad << ": " << e;
  }
}

TEST(MotionSettings, BadValuesNameTheKey) {
  TempDir dir;
  EXPECT_NE(test::settings_error(dir, kBase + "Motion.span: 0\n").find("Motion.span' is 0: must be in [1, 100]"),
            std::string::npos);
  EXPECT_NE(test::settings_error(dir, kBase + "Motion.minIou: 0\n").find("Motion.minIou"), std::string::npos);
  EXPECT_NE(test::settings_error(dir, kBase + "Motion.spam: 3\n").find("known keys"), std::string::npos);
}

}  // namespace
}  // namespace stillslam
