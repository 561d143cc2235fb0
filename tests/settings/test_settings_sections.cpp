// The Tracking, LocalMapping, LoopClosing and Viewer sections, the shipped
// segmentation model as default, and ORB-SLAM3 files as users have them.
#include <gtest/gtest.h>

#include <string>

#include "io/temp_dir.h"
#include "settings_test_files.h"
#include "stillslam/core/error.h"
#include "stillslam/settings/settings.h"

namespace stillslam {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

// ORB-SLAM3's Examples_old/RGB-D/TUM3.yaml as users have it: old-style
// keys, Viewer.* for its Pangolin window, no Segmentation.* keys.
const char* kOrbSlamTum3 = R"(%YAML:1.0

#--------------------------------------------------------------------------------------------
# Camera Parameters. Adjust them!
#--------------------------------------------------------------------------------------------

# Camera calibration and distortion parameters (OpenCV)
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

# Camera frames per second
Camera.fps: 30.0

# IR projector baseline times fx (aprox.)
Camera.bf: 40.0

# Color order of the images (0: BGR, 1: RGB. It is ignored if images are grayscale)
Camera.RGB: 1

# Close/Far threshold. Baseline times.
ThDepth: 40.0

# Deptmap values factor
DepthMapFactor: 5000.0

ORBextractor.nFeatures: 1000
ORBextractor.scaleFactor: 1.2
ORBextractor.nLevels: 8
ORBextractor.iniThFAST: 20
ORBextractor.minThFAST: 7

Viewer.KeyFrameSize: 0.05
Viewer.KeyFrameLineWidth: 1
Viewer.GraphLineWidth: 0.9
Viewer.PointSize:2
Viewer.CameraSize: 0.08
Viewer.CameraLineWidth: 3
Viewer.ViewpointX: 0
Viewer.ViewpointY: -0.7
Viewer.ViewpointZ: -1.8
Viewer.ViewpointF: 500
)";

// Where a built binary would be: the shipped model is found from it.
const fs::path kExecutable = STILLSLAM_SOURCE_DIR "/build/stillslam";

fs::path shipped_model() {
  return (fs::absolute(STILLSLAM_SOURCE_DIR) / "models/yolo11n-seg_384x512.onnx").lexically_normal();
}

TEST(SettingsDefaults, UnchangedOrbSlam3Tum3RunsWithTheShippedModel) {
  TempDir dir;
  const Settings s = load_settings(dir.write("TUM3.yaml", kOrbSlamTum3));
  EXPECT_DOUBLE_EQ(s.camera.fx, 535.4);
  EXPECT_DOUBLE_EQ(s.depth_map_factor, 5000.0);
  EXPECT_FALSE(s.stereo.has_value());
  EXPECT_TRUE(s.segmentation.enabled);
  EXPECT_EQ(fs::path(s.segmentation.model_path), shipped_model());
  EXPECT_TRUE(fs::is_regular_file(s.segmentation.model_path));
  EXPECT_EQ(s.segmentation.classes, std::vector<std::string>{"person"});
  EXPECT_EQ(s.viewer.port, ViewerOptions{}.port);  // ORB-SLAM3's Viewer keys are not ours
}

// ORB-SLAM3 v1.0 files carry System.*, IMU.* and Viewer.imageViewScale.
TEST(SettingsDefaults, OrbSlam3SystemAndImuKeysLoad) {
  TempDir dir;
  const std::string text = std::string(kOrbSlamTum3) +
                           "Viewer.imageViewScale: 1.0\nSystem.LoadAtlasFromFile: \"map\"\n"
                           "System.SaveAtlasToFile: \"map\"\nSystem.thFarPoints: 20.0\n"
                           "IMU.NoiseGyro: 1.7e-4\nIMU.Frequency: 200.0\nIMU.InsertKFsWhenLost: 0\n"
                           "Camera.newWidth: 600\nCamera.newHeight: 350\n";
  const Settings s = load_settings(dir.write("TUM3-v1.yaml", text));
  EXPECT_DOUBLE_EQ(s.camera.fx, 535.4);
  EXPECT_TRUE(s.segmentation.enabled);
}

TEST(SettingsDefaults, SectionsLeftOutKeepTodaysOptions) {
  TempDir dir;
  const Settings s = load_settings(dir.write("TUM3.yaml", kOrbSlamTum3));
  const TrackerOptions t;
  // Keyframes at least once a second, as System set it from Camera.fps.
  EXPECT_EQ(s.tracking.max_frames_between_keyframes, 30);
  EXPECT_EQ(s.tracking.init_min_keypoints, t.init_min_keypoints);
  EXPECT_EQ(s.tracking.min_local_map_inliers, t.min_local_map_inliers);
  EXPECT_EQ(s.tracking.max_local_keyframes, t.max_local_keyframes);
  EXPECT_FLOAT_EQ(s.tracking.motion_search_radius, t.motion_search_radius);
  EXPECT_DOUBLE_EQ(s.tracking.initial_view.max_masked_fraction, t.initial_view.max_masked_fraction);
  EXPECT_EQ(s.tracking.pose.rounds, t.pose.rounds);
  EXPECT_EQ(s.relocalization.min_inliers, RelocalizerOptions{}.min_inliers);
  const LocalMapperOptions m;
  EXPECT_EQ(s.local_mapping.bundle_adjustment.num_threads, 1);
  EXPECT_EQ(s.local_mapping.bundle_adjustment.iterations, m.bundle_adjustment.iterations);
  EXPECT_EQ(s.local_mapping.bundle_adjustment.iterations_after_outliers, m.bundle_adjustment.iterations_after_outliers);
  EXPECT_TRUE(s.local_mapping.enable_bundle_adjustment);
  EXPECT_TRUE(s.local_mapping.enable_keyframe_culling);
  EXPECT_DOUBLE_EQ(s.local_mapping.keyframe_culling.redundancy, m.keyframe_culling.redundancy);
  const LoopCloserOptions l;
  EXPECT_EQ(s.loop_closing.global_bundle_adjustment.num_threads, 1);
  EXPECT_EQ(s.loop_closing.global_bundle_adjustment.iterations, l.global_bundle_adjustment.iterations);
  EXPECT_TRUE(s.loop_closing.detect_loops);
  EXPECT_EQ(s.loop_closing.detector.min_inliers, l.detector.min_inliers);
  EXPECT_TRUE(s.map_merging);
  EXPECT_EQ(s.map_merger.detector.min_inliers, MapMergerOptions{}.detector.min_inliers);
  EXPECT_EQ(s.place_recognition.max_loop_candidates, PlaceRecognizerOptions{}.max_loop_candidates);
  EXPECT_EQ(s.viewer.port, 8080);
  EXPECT_EQ(s.viewer.host, "127.0.0.1");

  std::string text = kOrbSlamTum3;
  text.replace(text.find("Camera.fps: 30.0"), 16, "Camera.fps: 20.0");
  const Settings at20 = load_settings(dir.write("20fps.yaml", text));
  EXPECT_EQ(at20.tracking.max_frames_between_keyframes, 20);
}

TEST(SettingsDefaults, NoShippedModelIsAnErrorNamingPathAndFix) {
  TempDir dir;
  const std::string message = test::settings_error(dir, kOrbSlamTum3, "/nonexistent/bin/stillslam");
  EXPECT_NE(message.find("bad.yaml: key 'Segmentation.model' is not given"), std::string::npos) << message;
  EXPECT_NE(message.find("models/yolo11n-seg_384x512.onnx"), std::string::npos) << message;
  EXPECT_NE(message.find("/nonexistent/bin"), std::string::npos) << message;
  EXPECT_NE(message.find("set Segmentation.model"), std::string::npos) << message;
  EXPECT_NE(message.find("Segmentation.enabled: 0"), std::string::npos) << message;
  // Segmentation off: no model needed.
  EXPECT_EQ(test::settings_error(dir, std::string(kOrbSlamTum3) + "Segmentation.enabled: 0\n", "/nonexistent/bin/stillslam"),
            "");
  // A model given in the file wins over the shipped one.
  const Settings s = load_settings(dir.write("m.yaml", std::string(kOrbSlamTum3) + "Segmentation.model: m.onnx\n"));
  EXPECT_EQ(fs::path(s.segmentation.model_path), (fs::absolute(dir.path()) / "m.onnx").lexically_normal());
}

TEST(SettingsSections, TrackingKeysAreRead) {
  TempDir dir;
  const std::string text = std::string(kOrbSlamTum3) +
                           "Tracking.initMinKeypoints: 400\nTracking.initConfirmFrames: 3\n"
                           "Tracking.initWaitFrames: 20\nTracking.initMaxMaskedFraction: 0.4\n"
                           "Tracking.initMaxMovingShare: 0.1\nTracking.initMinMatches: 60\n"
                           "Tracking.initMaxReprojectionError: 3.5\nTracking.maxFramesBetweenKeyframes: 25\n"
                           "Tracking.minFramesBetweenKeyframes: 2\nTracking.closePointsTrackedMin: 90\n"
                           "Tracking.closePointsUntrackedMin: 60\nTracking.newKeyframePoints: 120\n"
                           "Tracking.motionSearchRadius: 8\nTracking.localMapSearchRadius: 4\n"
                           "Tracking.referenceSearchRadius: 6\nTracking.lostSearchRadius: 12\n"
                           "Tracking.minLocalMapInliers: 25\nTracking.maxLocalKeyframes: 60\n"
                           "Tracking.poseRounds: 3\nTracking.poseIterations: 8\n"
                           "Tracking.relocMinBowMatches: 12\nTracking.relocMinRansacInliers: 8\n"
                           "Tracking.relocMinInliers: 40\n";
  const Settings s = load_settings(dir.write("t.yaml", text));
  const TrackerOptions& t = s.tracking;
  EXPECT_EQ(t.init_min_keypoints, 400);
  EXPECT_EQ(t.init_confirm_frames, 3);
  EXPECT_EQ(t.init_wait_frames, 20);
  EXPECT_DOUBLE_EQ(t.initial_view.max_masked_fraction, 0.4);
  EXPECT_DOUBLE_EQ(t.initial_view.max_moving_share, 0.1);
  EXPECT_EQ(t.initial_view.min_matches, 60);
  EXPECT_DOUBLE_EQ(t.initial_view.max_reprojection_error_px, 3.5);
  EXPECT_EQ(t.max_frames_between_keyframes, 25);
  EXPECT_EQ(t.min_frames_between_keyframes, 2);
  EXPECT_EQ(t.close_points_tracked_min, 90);
  EXPECT_EQ(t.close_points_untracked_min, 60);
  EXPECT_EQ(t.new_keyframe_points, 120);
  EXPECT_FLOAT_EQ(t.motion_search_radius, 8.f);
  EXPECT_FLOAT_EQ(t.local_map_search_th, 4.f);
  EXPECT_FLOAT_EQ(t.reference_search_th, 6.f);
  EXPECT_FLOAT_EQ(t.lost_search_th, 12.f);
  EXPECT_EQ(t.min_local_map_inliers, 25);
  EXPECT_EQ(t.max_local_keyframes, 60u);
  EXPECT_EQ(t.pose.rounds, 3);
  EXPECT_EQ(t.pose.iterations_per_round, 8);
  EXPECT_EQ(s.relocalization.min_bow_matches, 12);
  EXPECT_EQ(s.relocalization.min_ransac_inliers, 8);
  EXPECT_EQ(s.relocalization.min_inliers, 40);
}

TEST(SettingsSections, LocalMappingKeysAreRead) {
  TempDir dir;
  const std::string text = std::string(kOrbSlamTum3) +
                           "LocalMapping.bundleAdjustment: 0\nLocalMapping.baThreads: 2\n"
                           "LocalMapping.baIterations: 7\nLocalMapping.baIterationsAfterOutliers: 4\n"
                           "LocalMapping.triangulationNeighbours: 15\nLocalMapping.fusionNeighbours: 12\n"
                           "LocalMapping.fusionSecondNeighbours: 3\nLocalMapping.pointMinFoundRatio: 0.3\n"
                           "LocalMapping.pointMinObservations: 4\nLocalMapping.keyframeCulling: 0\n"
                           "LocalMapping.keyframeRedundancy: 0.8\nLocalMapping.keyframeMinObservers: 2\n"
                           "LocalMapping.baSplitStereo: 1\nLocalMapping.baFunctionTolerance: 1e-5\n"
                           "LocalMapping.baMaxSeconds: 0.5\nLocalMapping.windowKeyframes: 9\n"
                           "LocalMapping.windowFixedKeyframes: 0\nLocalMapping.windowPoints: 1500\n"
                           "LocalMapping.windowObservations: 7000\nLocalMapping.pauseAbortsBundleAdjustment: 1\n"
                           "LocalMapping.baKeepInterrupted: 0\nLocalMapping.baIterationsBeforeInterrupt: 3\n"
                           "LocalMapping.threadNice: 7\n"
                           "LocalMapping.busyModel: 0\nLocalMapping.busyModelThreaded: 1\n"
                           "LocalMapping.busyModelKeyframeMs: 15\nLocalMapping.busyModelObservationUs: 4\n"
                           "LocalMapping.busyModelObservationIterationUs: 0.5\nLocalMapping.baSolver: ceres\n";
  const Settings s = load_settings(dir.write("m.yaml", text));
  const LocalMapperOptions& m = s.local_mapping;
  EXPECT_EQ(m.bundle_adjustment.solver, BaSolver::Ceres);
  EXPECT_TRUE(m.bundle_adjustment.split_stereo);
  EXPECT_DOUBLE_EQ(m.bundle_adjustment.function_tolerance, 1e-5);
  EXPECT_DOUBLE_EQ(m.bundle_adjustment.max_seconds_per_pass, 0.5);
  EXPECT_EQ(m.window.max_keyframes, 9);
  EXPECT_EQ(m.window.max_fixed_keyframes, 0);
  EXPECT_EQ(m.window.max_points, 1500);
  EXPECT_EQ(m.window.max_observations, 7000);
  EXPECT_TRUE(m.pause_aborts_bundle_adjustment);
  EXPECT_FALSE(m.bundle_adjustment.keep_progress_on_abort);
  EXPECT_EQ(m.iterations_before_interrupt, 3);
  EXPECT_EQ(m.thread_nice, 7);
  EXPECT_FALSE(m.busy_model);
  EXPECT_TRUE(m.busy_model_threaded);
  EXPECT_DOUBLE_EQ(m.busy.keyframe_ms, 15);
  EXPECT_DOUBLE_EQ(m.busy.observation_us, 4);
  EXPECT_DOUBLE_EQ(m.busy.observation_iteration_us, 0.5);
  EXPECT_FALSE(m.enable_bundle_adjustment);
  EXPECT_EQ(m.bundle_adjustment.num_threads, 2);
  EXPECT_EQ(m.bundle_adjustment.iterations, 7);
  EXPECT_EQ(m.bundle_adjustment.iterations_after_outliers, 4);
  EXPECT_EQ(m.triangulation.neighbours, 15u);
  EXPECT_EQ(m.fusion.neighbours, 12u);
  EXPECT_EQ(m.fusion.second_neighbours, 3u);
  EXPECT_DOUBLE_EQ(m.point_culling.min_found_ratio, 0.3);
  EXPECT_EQ(m.point_culling.min_observations, 4);
  EXPECT_FALSE(m.enable_keyframe_culling);
  EXPECT_DOUBLE_EQ(m.keyframe_culling.redundancy, 0.8);
  EXPECT_EQ(m.keyframe_culling.min_observers, 2);
}

TEST(SettingsSections, LoopClosingKeysAreRead) {
  TempDir dir;
  // Nested layout: the same keys under a "LoopClosing:" map.
  const std::string text = std::string(kOrbSlamTum3) +
                           "LoopClosing:\n  detectLoops: 0\n  maxCandidates: 5\n  minCommonWordsRatio: 0.7\n"
                           "  minKeyframesBetweenLoops: 15\n  consistencyThreshold: 2\n  minBowMatches: 25\n"
                           "  projectionWindow: 8\n  minInliers: 45\n  confirmationNeighbours: 6\n"
                           "  minConfirmationMatches: 20\n  fuseWindow: 3\n  poseGraphIterations: 30\n"
                           "  globalBundleAdjustment: 0\n  baThreads: 2\n  baIterations: 12\n"
                           "  mapMerging: 0\n  mergeMinInliers: 50\n  mergeGlobalBundleAdjustment: 0\n";
  const Settings s = load_settings(dir.write("l.yaml", text));
  const LoopCloserOptions& l = s.loop_closing;
  EXPECT_FALSE(l.detect_loops);
  EXPECT_EQ(s.place_recognition.max_loop_candidates, 5u);
  EXPECT_DOUBLE_EQ(s.place_recognition.min_common_words_ratio, 0.7);
  EXPECT_EQ(l.detector.min_keyframes_between_loops, 15);
  EXPECT_EQ(l.detector.consistency_threshold, 2);
  EXPECT_EQ(l.detector.min_bow_matches, 25);
  EXPECT_FLOAT_EQ(l.detector.projection_window, 8.f);
  EXPECT_EQ(l.detector.min_inliers, 45);
  EXPECT_EQ(l.detector.confirmation_neighbours, 6u);
  EXPECT_EQ(l.detector.min_confirmation_matches, 20);
  EXPECT_FLOAT_EQ(l.correction.fuse_window, 3.f);
  EXPECT_EQ(l.correction.pose_graph_iterations, 30);
  EXPECT_FALSE(l.run_global_bundle_adjustment);
  EXPECT_EQ(l.global_bundle_adjustment.num_threads, 2);
  EXPECT_EQ(l.global_bundle_adjustment.iterations, 12);
  EXPECT_FALSE(s.map_merging);
  EXPECT_EQ(s.map_merger.detector.min_inliers, 50);
  EXPECT_EQ(s.map_merger.detector.min_bow_matches, MapMergerOptions{}.detector.min_bow_matches);
  EXPECT_FALSE(s.map_merger.global_bundle_adjustment);
}

TEST(SettingsSections, ViewerKeysAreRead) {
  TempDir dir;
  const Settings s = load_settings(
      dir.write("v.yaml", std::string(kOrbSlamTum3) + "Viewer.port: 9000\nViewer.host: \"0.0.0.0\"\n"));
  EXPECT_EQ(s.viewer.port, 9000);
  EXPECT_EQ(s.viewer.host, "0.0.0.0");
}

TEST(SettingsSections, MisspeltKeysListTheKnownOnes) {
  TempDir dir;
  const std::string base = kOrbSlamTum3;
  struct Case {
    std::string text, key, known;
  };
  const std::vector<Case> cases = {
      {base + "Tracking.minLocalMapInlier: 20\n", "Tracking.minLocalMapInlier",
       "is not a known Tracking setting (known keys: Tracking.initMinKeypoints, Tracking.initConfirmFrames,"},
      {base + "Tracking:\n  poseRound: 2\n", "Tracking.poseRound", "Tracking.poseRounds"},
      {base + "LocalMapping.baThread: 2\n", "LocalMapping.baThread",
       "is not a known LocalMapping setting (known keys: LocalMapping.bundleAdjustment, LocalMapping.baThreads,"},
      {base + "LocalMapping:\n  culling: 0\n", "LocalMapping.culling", "LocalMapping.keyframeCulling"},
      {base + "LoopClosing.mapMerge: 0\n", "LoopClosing.mapMerge",
       "is not a known LoopClosing setting (known keys: LoopClosing.detectLoops, LoopClosing.maxCandidates,"},
      {base + "LoopClosing:\n  baThread: 2\n", "LoopClosing.baThread", "LoopClosing.mergeGlobalBundleAdjustment)"},
      {base + "Segmentation.modell: m.onnx\n", "Segmentation.modell", "Segmentation.model,"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.key);
    const std::string message = test::settings_error(dir, c.text, kExecutable);
    EXPECT_NE(message.find("bad.yaml: key '" + c.key + "'"), std::string::npos) << message;
    EXPECT_NE(message.find(c.known), std::string::npos) << message;
  }
  // Viewer.* is ORB-SLAM3's too: another key there only warns.
  EXPECT_EQ(test::settings_error(dir, base + "Viewer.prot: 9000\n", kExecutable), "");
}

TEST(SettingsSections, BadValuesNameFileKeyValueAndRange) {
  TempDir dir;
  const std::string base = kOrbSlamTum3;
  struct Case {
    std::string text, key, hint;
  };
  const std::vector<Case> cases = {
      {base + "Tracking.minLocalMapInliers: 0\n", "Tracking.minLocalMapInliers", "is 0: must be in [1, 50000]"},
      {base + "Tracking.initMaxMaskedFraction: 1.5\n", "Tracking.initMaxMaskedFraction", "is 1.5: must be in [0, 1]"},
      {base + "Tracking.minFramesBetweenKeyframes: 40\n", "Tracking.minFramesBetweenKeyframes",
       "is 40: must be in [0, 30]"},
      {base + "Tracking.maxLocalKeyframes: -3\n", "Tracking.maxLocalKeyframes", "is -3: must be in [1, 10000]"},
      {base + "Tracking.motionSearchRadius: \"wide\"\n", "Tracking.motionSearchRadius", "must be a number"},
      {base + "Tracking.relocMinInliers: 0\n", "Tracking.relocMinInliers", "is 0: must be in [1, 50000]"},
      {base + "LocalMapping.baThreads: 0\n", "LocalMapping.baThreads", "is 0: must be in [1, "},
      {base + "LocalMapping.keyframeRedundancy: 0\n", "LocalMapping.keyframeRedundancy", "is 0: must be in (0, 1]"},
      {base + "LocalMapping.bundleAdjustment: 2\n", "LocalMapping.bundleAdjustment", "must be 0 or 1"},
      {base + "Tracking.motionPriorRefit: 2\n", "Tracking.motionPriorRefit", "must be 0 or 1"},
      {base + "LoopClosing.baThreads: 0\n", "LoopClosing.baThreads", "is 0: must be in [1, "},
      {base + "LoopClosing.minInliers: 0\n", "LoopClosing.minInliers", "is 0: must be in [1, 50000]"},
      {base + "LoopClosing.mergeMinInliers: -1\n", "LoopClosing.mergeMinInliers", "is -1: must be in [1, 50000]"},
      {base + "LoopClosing.minCommonWordsRatio: 2\n", "LoopClosing.minCommonWordsRatio", "is 2: must be in [0, 1]"},
      {base + "LoopClosing: 1\n", "LoopClosing", "must be a map"},
      {base + "Viewer.port: 70000\n", "Viewer.port", "is 70000: must be in [0, 65535]"},
      {base + "Viewer.host: 12\n", "Viewer.host", "must be a string"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.key);
    const std::string message = test::settings_error(dir, c.text, kExecutable);
    EXPECT_NE(message.find("bad.yaml: key '" + c.key + "' "), std::string::npos) << message;
    EXPECT_NE(message.find(c.hint), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace stillslam
