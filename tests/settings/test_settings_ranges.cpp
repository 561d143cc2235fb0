// Every settings key has a range from what a real camera and a sane ORB /
// SLAM configuration can be: a value outside it is an error naming the file,
// the key, the value and the range. The shipped presets and the simulator's
// settings load.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/temp_dir.h"
#include "settings_test_files.h"
#include "stillslam/core/error.h"
#include "stillslam/settings/settings.h"
#include "stillslam/sim/settings_files.h"
#include "stillslam/sim/simulation_options.h"

namespace stillslam {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

// A valid RGB-D file; each case appends one key (a later key wins in OpenCV's
// YAML, so camera keys are replaced instead).
const std::string& kBase = test::kRgbdSettings;

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

struct Case {
  std::string key, value, hint;  // hint: part of the message after "key '<key>' "
};

// Appended keys: one value below and one above each key's range.
const std::vector<Case> kSectionCases = {
    // The values reported in issue #15.
    {"ORBextractor.nFeatures", "1", "is 1: must be in [100, 50000]"},
    {"ORBextractor.nFeatures", "2000000000", "is 2e+09: must be in [100, 50000]"},
    {"Segmentation.maskDilation", "1000000", "is 1000000: must be in [0, 256]"},
    {"Segmentation.threads", "100000", "is 100000: must be in [0, "},
    // The rest of ORBextractor.* and Segmentation.*.
    {"ORBextractor.scaleFactor", "3", "is 3: must be in [1, 2]"},
    {"ORBextractor.scaleFactor", "0.5", "is 0.5: must be in [1, 2]"},
    {"ORBextractor.nLevels", "0", "is 0: must be in [1, 16]"},
    {"ORBextractor.nLevels", "40", "is 40: must be in [1, 16]"},
    {"ORBextractor.iniThFAST", "0", "is 0: must be in [1, 254]"},
    {"ORBextractor.iniThFAST", "300", "is 300: must be in [1, 254]"},
    {"ORBextractor.minThFAST", "0", "is 0: must be in [1, 254]"},
    {"ORBextractor.minThFAST", "1000", "is 1000: must be in [1, 254]"},
    {"Segmentation.scoreThreshold", "-0.1", "is -0.1: must be in [0, 1]"},
    {"Segmentation.nmsIouThreshold", "0", "is 0: must be in (0, 1]"},
    {"Segmentation.maskThreshold", "2", "is 2: must be in (0, 1]"},
    {"Segmentation.maskDilation", "-1", "is -1: must be in [0, 256]"},
    {"Segmentation.holdFrames", "-1", "is -1: must be in [0, 1000]"},
    {"Segmentation.holdFrames", "100000", "is 100000: must be in [0, 1000]"},
    {"Segmentation.threads", "-2", "is -2: must be in [0, "},
    {"Segmentation.threadNice", "-1", "is -1: must be in [0, 19]"},
    {"Segmentation.threadNice", "20", "is 20: must be in [0, 19]"},
    // Tracking.*
    {"Tracking.initMinKeypoints", "0", "is 0: must be in [1, 50000]"},
    {"Tracking.initMinKeypoints", "1e9", "is 1e+09: must be in [1, 50000]"},
    {"Tracking.initConfirmFrames", "-1", "is -1: must be in [0, 100]"},
    {"Tracking.initConfirmFrames", "1000", "is 1000: must be in [0, 100]"},
    {"Tracking.initUnmaskedConfirmFrames", "-1", "is -1: must be in [0, 100]"},
    {"Tracking.initUnmaskedConfirmFrames", "1000", "is 1000: must be in [0, 100]"},
    {"Tracking.initUnmaskedTrustFrames", "-1", "is -1: must be in [0, 1000]"},
    {"Tracking.initUnmaskedTrustFrames", "5000", "is 5000: must be in [0, 1000]"},
    {"Tracking.initUnmaskedMovingShare", "-0.1", "is -0.1: must be in [0, 1]"},
    {"Tracking.initUnmaskedMovingShare", "1.5", "is 1.5: must be in [0, 1]"},
    {"Tracking.initUnmaskedMovingPoints", "-1", "is -1: must be in [0, 100000]"},
    {"Tracking.initUnmaskedMovingPoints", "1e9", "is 1e+09: must be in [0, 100000]"},
    {"Tracking.initWaitFrames", "-1", "is -1: must be in [0, 100000]"},
    {"Tracking.initWaitFrames", "1e9", "is 1e+09: must be in [0, 100000]"},
    {"Tracking.initMaxMaskedFraction", "1.5", "is 1.5: must be in [0, 1]"},
    {"Tracking.initMaxMovingShare", "-1", "is -1: must be in [0, 1]"},
    {"Tracking.initMaxMovingShareUnmasked", "1.5", "is 1.5: must be in [0, 1]"},
    {"Tracking.initMinMatches", "0", "is 0: must be in [1, 50000]"},
    {"Tracking.initMinMatches", "1e6", "is 1000000: must be in [1, 50000]"},
    {"Tracking.initMaxReprojectionError", "0", "is 0: must be in (0, 100]"},
    {"Tracking.initMaxReprojectionError", "1e4", "is 10000: must be in (0, 100]"},
    {"Tracking.initMaxReprojectionErrorUnmasked", "0", "is 0: must be in (0, 100]"},
    {"Tracking.initMovingFactorUnmasked", "0.5", "is 0.5: must be in [1, 100]"},
    {"Tracking.initMovingFactorUnmasked", "101", "is 101: must be in [1, 100]"},
    {"Tracking.maxFramesBetweenKeyframes", "-1", "is -1: must be in [0, 100000]"},
    {"Tracking.maxFramesBetweenKeyframes", "1e9", "is 1e+09: must be in [0, 100000]"},
    {"Tracking.minFramesBetweenKeyframes", "-1", "is -1: must be in [0, 100000]"},
    {"Tracking.closePointsTrackedMin", "-1", "is -1: must be in [0, 50000]"},
    {"Tracking.closePointsTrackedMin", "1e6", "is 1000000: must be in [0, 50000]"},
    {"Tracking.closePointsUntrackedMin", "-1", "is -1: must be in [0, 50000]"},
    {"Tracking.closePointsUntrackedMin", "1e6", "is 1000000: must be in [0, 50000]"},
    {"Tracking.newKeyframePoints", "-1", "is -1: must be in [0, 50000]"},
    {"Tracking.interruptInliers", "-1", "is -1: must be in [0, 50000]"},
    {"Tracking.keyframeBudgetInliers", "-1", "is -1: must be in [0, 50000]"},
    {"Tracking.keyframeBudgetInliers", "1e6", "is 1000000: must be in [0, 50000]"},
    {"Tracking.keyframesPerSecond", "-1", "is -1: must be in [0, 1000]"},
    {"Tracking.keyframeBudgetStartKeyframes", "-1", "is -1: must be in [0, 1000]"},
    {"Tracking.keyframeBudgetStartKeyframes", "5000", "is 5000: must be in [0, 1000]"},
    {"Tracking.keyframeBudgetStartSeconds", "-0.5", "is -0.5: must be in [0, 1000]"},
    {"Tracking.keyframeBudgetStartSeconds", "5000", "is 5000: must be in [0, 1000]"},
    {"Tracking.newKeyframePoints", "1e6", "is 1000000: must be in [0, 50000]"},
    {"Tracking.motionSearchRadius", "0", "is 0: must be in (0, 1000]"},
    {"Tracking.motionSearchRadius", "1e6", "is 1000000: must be in (0, 1000]"},
    {"Tracking.localMapSearchRadius", "-3", "is -3: must be in (0, 1000]"},
    {"Tracking.localMapSearchRadius", "5000", "is 5000: must be in (0, 1000]"},
    {"Tracking.referenceSearchRadius", "0", "is 0: must be in (0, 1000]"},
    {"Tracking.referenceSearchRadius", "5000", "is 5000: must be in (0, 1000]"},
    {"Tracking.lostSearchRadius", "0", "is 0: must be in (0, 1000]"},
    {"Tracking.lostSearchRadius", "5000", "is 5000: must be in (0, 1000]"},
    {"Tracking.minLocalMapInliers", "0", "is 0: must be in [1, 50000]"},
    {"Tracking.minLocalMapInliers", "1e6", "is 1000000: must be in [1, 50000]"},
    {"Tracking.maxLocalKeyframes", "0", "is 0: must be in [1, 10000]"},
    {"Tracking.maxLocalKeyframes", "1e6", "is 1000000: must be in [1, 10000]"},
    {"Tracking.poseRounds", "0", "is 0: must be in [1, 100]"},
    {"Tracking.poseRounds", "1000", "is 1000: must be in [1, 100]"},
    {"Tracking.poseIterations", "0", "is 0: must be in [1, 1000]"},
    {"Tracking.poseIterations", "1e6", "is 1000000: must be in [1, 1000]"},
    {"Tracking.motionPriorSigma", "-0.001", "is -0.001: must be in [0, 10]"},
    {"Tracking.motionPriorSigma", "100", "is 100: must be in [0, 10]"},
    {"Tracking.motionPriorRotationSigma", "0", "is 0: must be in (0, 10]"},
    {"Tracking.motionPriorDeadZone", "-1", "is -1: must be in [0, 10]"},
    {"Tracking.motionPriorGate", "-0.01", "is -0.01: must be in [0, 10]"},
    {"Tracking.motionPriorGate", "20", "is 20: must be in [0, 10]"},
    {"Tracking.relocMinBowMatches", "0", "is 0: must be in [1, 50000]"},
    {"Tracking.relocMinBowMatches", "1e6", "is 1000000: must be in [1, 50000]"},
    {"Tracking.relocMinRansacInliers", "0", "is 0: must be in [1, 50000]"},
    {"Tracking.relocMinRansacInliers", "1e6", "is 1000000: must be in [1, 50000]"},
    {"Tracking.relocMinInliers", "0", "is 0: must be in [1, 50000]"},
    {"Tracking.relocMinInliers", "1e6", "is 1000000: must be in [1, 50000]"},
    // LocalMapping.*
    {"LocalMapping.baThreads", "0", "is 0: must be in [1, "},
    {"LocalMapping.threadNice", "-5", "is -5: must be in [0, 19]"},
    {"LocalMapping.threadNice", "40", "is 40: must be in [0, 19]"},
    {"LocalMapping.baSolver", "cholmod", "must be schur (the hand-written Schur-complement solver) or ceres"},
    {"LocalMapping.busyModelKeyframeMs", "-1", "is -1: must be in [0, 10000]"},
    {"LocalMapping.busyModelObservationUs", "2000", "is 2000: must be in [0, 1000]"},
    {"LocalMapping.busyModelObservationIterationUs", "-0.5", "is -0.5: must be in [0, 1000]"},
    {"LocalMapping.baThreads", "100000", "is 100000: must be in [1, "},
    {"LocalMapping.baIterations", "0", "is 0: must be in [1, 1000]"},
    {"LocalMapping.baIterations", "1e6", "is 1000000: must be in [1, 1000]"},
    {"LocalMapping.baIterationsAfterOutliers", "-1", "is -1: must be in [0, 1000]"},
    {"LocalMapping.baIterationsAfterOutliers", "1e6", "is 1000000: must be in [0, 1000]"},
    {"LocalMapping.baFunctionTolerance", "2", "is 2: must be in [0, 1]"},
    {"LocalMapping.baMaxSeconds", "-1", "is -1: must be in [0, 60]"},
    {"LocalMapping.bundleAdjustmentsPerSecond", "-1", "is -1: must be in [0, 1000]"},
    {"LocalMapping.bundleAdjustmentsPerSecond", "2000", "is 2000: must be in [0, 1000]"},
    {"LocalMapping.windowKeyframes", "-1", "is -1: must be in [0, 1000]"},
    {"LocalMapping.windowObservations", "6000000", "is 6000000: must be in [0, 5000000]"},
    {"LocalMapping.triangulationNeighbours", "0", "is 0: must be in [1, 1000]"},
    {"LocalMapping.triangulationNeighbours", "1e6", "is 1000000: must be in [1, 1000]"},
    {"LocalMapping.fusionNeighbours", "0", "is 0: must be in [1, 1000]"},
    {"LocalMapping.fusionNeighbours", "1e6", "is 1000000: must be in [1, 1000]"},
    {"LocalMapping.fusionSecondNeighbours", "-1", "is -1: must be in [0, 1000]"},
    {"LocalMapping.fusionSecondNeighbours", "1e6", "is 1000000: must be in [0, 1000]"},
    {"LocalMapping.pointMinFoundRatio", "-0.5", "is -0.5: must be in [0, 1]"},
    {"LocalMapping.pointMinFoundRatio", "2", "is 2: must be in [0, 1]"},
    {"LocalMapping.pointMinObservations", "-1", "is -1: must be in [0, 1000]"},
    {"LocalMapping.pointMinObservations", "1e6", "is 1000000: must be in [0, 1000]"},
    {"LocalMapping.keyframeRedundancy", "0", "is 0: must be in (0, 1]"},
    {"LocalMapping.keyframeRedundancy", "1.5", "is 1.5: must be in (0, 1]"},
    {"LocalMapping.keyframeMinObservers", "0", "is 0: must be in [1, 1000]"},
    {"LocalMapping.keyframeMinObservers", "1e6", "is 1000000: must be in [1, 1000]"},
    // LoopClosing.*
    {"LoopClosing.maxCandidates", "0", "is 0: must be in [1, 1000]"},
    {"LoopClosing.maxCandidates", "1e6", "is 1000000: must be in [1, 1000]"},
    {"LoopClosing.minCommonWordsRatio", "2", "is 2: must be in [0, 1]"},
    {"LoopClosing.minKeyframesBetweenLoops", "-1", "is -1: must be in [0, 100000]"},
    {"LoopClosing.minKeyframesBetweenLoops", "1e9", "is 1e+09: must be in [0, 100000]"},
    {"LoopClosing.consistencyThreshold", "0", "is 0: must be in [1, 100]"},
    {"LoopClosing.consistencyThreshold", "1000", "is 1000: must be in [1, 100]"},
    {"LoopClosing.minBowMatches", "0", "is 0: must be in [1, 50000]"},
    {"LoopClosing.minBowMatches", "1e6", "is 1000000: must be in [1, 50000]"},
    {"LoopClosing.projectionWindow", "0", "is 0: must be in (0, 1000]"},
    {"LoopClosing.projectionWindow", "1e6", "is 1000000: must be in (0, 1000]"},
    {"LoopClosing.minInliers", "0", "is 0: must be in [1, 50000]"},
    {"LoopClosing.minInliers", "1e6", "is 1000000: must be in [1, 50000]"},
    {"LoopClosing.confirmationNeighbours", "-1", "is -1: must be in [0, 1000]"},
    {"LoopClosing.confirmationNeighbours", "1e6", "is 1000000: must be in [0, 1000]"},
    {"LoopClosing.minConfirmationMatches", "-1", "is -1: must be in [0, 50000]"},
    {"LoopClosing.minConfirmationMatches", "1e6", "is 1000000: must be in [0, 50000]"},
    {"LoopClosing.fuseWindow", "0", "is 0: must be in (0, 1000]"},
    {"LoopClosing.fuseWindow", "1e6", "is 1000000: must be in (0, 1000]"},
    {"LoopClosing.poseGraphIterations", "0", "is 0: must be in [1, 10000]"},
    {"LoopClosing.poseGraphIterations", "1e6", "is 1000000: must be in [1, 10000]"},
    {"LoopClosing.baThreads", "0", "is 0: must be in [1, "},
    {"LoopClosing.baThreads", "100000", "is 100000: must be in [1, "},
    {"LoopClosing.baIterations", "0", "is 0: must be in [1, 1000]"},
    {"LoopClosing.baIterations", "1e6", "is 1000000: must be in [1, 1000]"},
    {"LoopClosing.mergeMinInliers", "0", "is 0: must be in [1, 50000]"},
    {"LoopClosing.mergeMinInliers", "1e6", "is 1000000: must be in [1, 50000]"},
    {"Viewer.port", "-1", "is -1: must be in [0, 65535]"},
    {"Viewer.image_rate", "0", "is 0: must be in [0.1, 60]"},
    {"Viewer.map_rate", "100", "is 100: must be in [0.1, 30]"},
    {"Viewer.jpeg_quality", "5", "is 5: must be in [10, 100]"},
};

TEST(SettingsRanges, EverySectionKeyOutOfRangeNamesKeyValueAndRange) {
  TempDir dir;
  for (const Case& c : kSectionCases) {
    SCOPED_TRACE(c.key + ": " + c.value);
    const std::string message = test::settings_error(dir, kBase + c.key + ": " + c.value + "\n");
    EXPECT_NE(message.find("bad.yaml: key '" + c.key + "' " + c.hint), std::string::npos) << message;
  }
}

// Camera keys replace the base's line (or are added when the base has none).
struct CameraCase {
  std::string from, to, key, hint;
};

const std::vector<CameraCase> kCameraCases = {
    // The values reported in issue #15.
    {"Camera.fx: 535.4", "Camera.fx: 1e300", "Camera.fx", "is 1e+300: must be in [10, 100000] (focal length"},
    {"Camera.fx: 535.4", "Camera.fx: 1e-300", "Camera.fx", "is 1e-300: must be in [10, 100000]"},
    {"Camera.cx: 320.1", "Camera.cx: -1e12", "Camera.cx", "is -1e+12: must be in [0, 640] (principal point inside"},
    {"DepthMapFactor: 5000.0", "DepthMapFactor: 1e300", "DepthMapFactor", "is 1e+300: must be in [1, 100000]"},
    {"DepthMapFactor: 5000.0", "DepthMapFactor: 1e-300", "DepthMapFactor", "is 1e-300: must be in [1, 100000]"},
    {"Camera.p2: 0.0", "Camera.p2: -1", "Camera.p2", "is -1: this distortion folds the image at pixel"},
    // The rest of the camera.
    {"Camera.fy: 539.2", "Camera.fy: 1", "Camera.fy", "is 1: must be in [10, 100000]"},
    {"Camera.cy: 247.6", "Camera.cy: 481", "Camera.cy", "is 481: must be in [0, 480]"},
    {"Camera.k1: 0.0", "Camera.k1: -3", "Camera.k1", "is -3: this distortion folds the image at pixel"},
    {"Camera.width: 640", "Camera.width: 1", "Camera.width", "is 1: must be in [16, 20000]"},
    {"Camera.height: 480", "Camera.height: 1000000", "Camera.height", "is 1000000: must be in [16, 20000]"},
    {"Camera.fps: 30.0", "Camera.fps: 0", "Camera.fps", "is 0: must be in [0.1, 1000]"},
    {"Camera.fps: 30.0", "Camera.fps: 1e9", "Camera.fps", "is 1e+09: must be in [0.1, 1000]"},
    {"ThDepth: 40.0", "ThDepth: 0", "ThDepth", "is 0: must be in [1, 1000]"},
    {"ThDepth: 40.0", "ThDepth: 1e9", "ThDepth", "is 1e+09: must be in [1, 1000]"},
    {"Camera.bf: 40.0", "Camera.bf: 1e6", "Camera.bf", "is 1000000: must be in [0.5354, 5354] (baseline"},
    {"Camera.bf: 40.0", "Camera.bf: 0.01", "Camera.bf", "is 0.01: must be in [0.5354, 5354]"},
    {"Camera.bf: 40.0", "Stereo.b: 50", "Stereo.b", "is 50: must be in [0.001, 10] (stereo baseline in metres)"},
};

TEST(SettingsRanges, CameraKeysOutOfRangeNameKeyValueAndRange) {
  TempDir dir;
  for (const CameraCase& c : kCameraCases) {
    SCOPED_TRACE(c.to);
    const std::string message = test::settings_error(dir, replaced(kBase, c.from, c.to));
    EXPECT_NE(message.find("bad.yaml: key '" + c.key + "' " + c.hint), std::string::npos) << message;
  }
}

TEST(SettingsRanges, FoldingDistortionNamesTheCoefficient) {
  TempDir dir;
  // EuRoC cam0 with p2 = -1 (a sign or order mix-up): p2 is named, not k1.
  const std::string euroc = replaced(kBase, "Camera.k1: 0.0\nCamera.k2: 0.0\nCamera.p1: 0.0\nCamera.p2: 0.0",
                                     "Camera.k1: -0.28340811\nCamera.k2: 0.07395907\nCamera.p1: 0.00019359\n"
                                     "Camera.p2: -1");
  const std::string m = test::settings_error(dir, euroc);
  EXPECT_NE(m.find("key 'Camera.p2' is -1: this distortion folds the image"), std::string::npos) << m;
  // EuRoC's real coefficients load.
  const std::string real = replaced(euroc, "Camera.p2: -1", "Camera.p2: 1.76187114e-05");
  EXPECT_NO_THROW(load_settings(dir.write("real.yaml", real)));
  // Fisheye (KannalaBrandt8) whose angle turns back inside the view.
  const std::string kb8 = replaced(kBase, "%YAML:1.0\n", "%YAML:1.0\nCamera.type: \"KannalaBrandt8\"\n");
  const std::string fisheye = replaced(kb8, "Camera.p1: 0.0\nCamera.p2: 0.0", "Camera.k3: 0.0\nCamera.k4: -2.0");
  const std::string f = test::settings_error(dir, fisheye);
  EXPECT_NE(f.find("key 'Camera.k4' is -2: this distortion folds the image at "), std::string::npos) << f;
}

TEST(SettingsRanges, ShippedPresetsAndSimulatorSettingsLoad) {
  const fs::path config = fs::path(STILLSLAM_SOURCE_DIR) / "config";
  int presets = 0;
  for (const auto& entry : fs::directory_iterator(config)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW(load_settings(entry.path()));
    ++presets;
  }
  EXPECT_EQ(presets, 10);  // TUM x3, EuRoC, KITTI x3, ZED 2i 720p, VGA, 720p low-texture
  TempDir dir;
  const fs::path model = fs::path(STILLSLAM_SOURCE_DIR) / "models" / "yolo11n-seg_384x512.onnx";
  const sim::SimulationOptions options;
  const CameraCalibration camera = sim::camera_from_options(options);
  sim::write_rgbd_settings(dir.path() / "rgbd.yaml", camera, options, model);
  sim::write_stereo_settings(dir.path() / "stereo.yaml", camera, options, model);
  const Settings rgbd = load_settings(dir.path() / "rgbd.yaml");
  EXPECT_TRUE(rgbd.rgbd);
  EXPECT_EQ(rgbd.orb.n_features, 1000);
  const Settings stereo = load_settings(dir.path() / "stereo.yaml");
  EXPECT_TRUE(stereo.stereo.has_value());
  EXPECT_EQ(stereo.orb.n_features, 2000);
}

}  // namespace
}  // namespace stillslam
