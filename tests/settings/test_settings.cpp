#include <gtest/gtest.h>

#include <string>

#include "io/temp_dir.h"
#include "settings_test_files.h"
#include "stillslam/core/error.h"
#include "stillslam/settings/settings.h"

namespace stillslam {
namespace {

using test::TempDir;

// ORB-SLAM2 style RGB-D file, as RGB-D-TUM1.yaml (no Camera.type, old keys,
// a Viewer key without a space, an unrelated key at the end).
const char* kOldTum = R"(%YAML:1.0
Camera.fx: 517.306408
Camera.fy: 516.469215
Camera.cx: 318.643040
Camera.cy: 255.313989
Camera.k1: 0.262383
Camera.k2: -0.953104
Camera.p1: -0.005358
Camera.p2: 0.002628
Camera.k3: 1.163314
Camera.width: 640
Camera.height: 480
Camera.fps: 30.0
Camera.bf: 40.0
Camera.RGB: 1
ThDepth: 40.0
DepthMapFactor: 5000.0
ORBextractor.nFeatures: 1000
ORBextractor.scaleFactor: 1.2
ORBextractor.nLevels: 8
ORBextractor.iniThFAST: 20
ORBextractor.minThFAST: 7
Viewer.KeyFrameSize: 0.05
Viewer.PointSize:2
Viewer.ViewpointF: 500
Map.mapfile: test.map
)";

// Old-style stereo EuRoC with the LEFT/RIGHT rectification blocks.
const char* kOldEuroc = R"(%YAML:1.0
Camera.type: "PinHole"
Camera.fx: 435.2046959714599
Camera.fy: 435.2046959714599
Camera.cx: 367.4517211914062
Camera.cy: 252.2008514404297
Camera.k1: 0.0
Camera.k2: 0.0
Camera.p1: 0.0
Camera.p2: 0.0
Camera.bFishEye: 0
Camera.width: 752
Camera.height: 480
Camera.fps: 20.0
Camera.bf: 47.90639384423901
Camera.RGB: 1
ThDepth: 35
LEFT.height: 480
LEFT.width: 752
LEFT.D: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data:[-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05, 0.0]
LEFT.K: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [458.654, 0.0, 367.215, 0.0, 457.296, 248.375, 0.0, 0.0, 1.0]
LEFT.R:  !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [0.999966347530033, -0.001422739138722922, 0.008079580483432283, 0.001365741834644127, 0.9999741760894847, 0.007055629199258132, -0.008089410156878961, -0.007044357138835809, 0.9999424675829176]
LEFT.P:  !!opencv-matrix
   rows: 3
   cols: 4
   dt: d
   data: [435.2046959714599, 0, 367.4517211914062, 0,  0, 435.2046959714599, 252.2008514404297, 0,  0, 0, 1, 0]
RIGHT.height: 480
RIGHT.width: 752
RIGHT.D: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data:[-0.28368365, 0.07451284, -0.00010473, -3.555907e-05, 0.0]
RIGHT.K: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [457.587, 0.0, 379.999, 0.0, 456.134, 255.238, 0.0, 0.0, 1]
RIGHT.R:  !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [0.9999633526194376, -0.003625811871560086, 0.007755443660172947, 0.003680398547259526, 0.9999684752771629, -0.007035845251224894, -0.007729688520722713, 0.007064130529506649, 0.999945173484644]
RIGHT.P:  !!opencv-matrix
   rows: 3
   cols: 4
   dt: d
   data: [435.2046959714599, 0, 367.4517211914062, -47.90639384423901, 0, 435.2046959714599, 252.2008514404297, 0, 0, 0, 1, 0]
ORBextractor.nFeatures: 1200
ORBextractor.scaleFactor: 1.2
ORBextractor.nLevels: 8
ORBextractor.iniThFAST: 20
ORBextractor.minThFAST: 7
)";

// New-style KITTI, as ORB-SLAM3's Stereo/KITTI00-02.yaml.
const char* kNewKitti = R"(%YAML:1.0
File.version: "1.0"
Camera.type: "Rectified"
Camera1.fx: 718.856
Camera1.fy: 718.856
Camera1.cx: 607.1928
Camera1.cy: 185.2157
Camera.width: 1241
Camera.height: 376
Camera.fps: 10
Stereo.b: 0.53716
Camera.RGB: 1
Stereo.ThDepth: 35.0
ORBextractor.nFeatures: 2000
ORBextractor.scaleFactor: 1.2
ORBextractor.nLevels: 8
ORBextractor.iniThFAST: 20
ORBextractor.minThFAST: 7
)";

const char* kNewFisheye = R"(%YAML:1.0
File.version: "1.0"
Camera.type: "KannalaBrandt8"
Camera1.fx: 190.97847715128717
Camera1.fy: 190.9733070521226
Camera1.cx: 254.93170605935475
Camera1.cy: 256.8974428996504
Camera1.k1: 0.0034823894022493434
Camera1.k2: 0.0007150348452162257
Camera1.k3: -0.0020532361418706202
Camera1.k4: 0.00020293673591811182
Camera2.fx: 190.44236969414825
Camera2.fy: 190.4344384721956
Camera2.cx: 252.59949716835982
Camera2.cy: 254.91723064636983
Camera2.k1: 0.0034003170790442797
Camera2.k2: 0.001766278153469831
Camera2.k3: -0.00266312569781606
Camera2.k4: 0.0003299517423931039
Stereo.T_c1_c2: !!opencv-matrix
  rows: 4
  cols: 4
  dt: f
  data: [0.999997256477797,-0.002317135723275,-0.000343393120620, 0.101,
         0.002312067192432, 0.999898048507103,-0.014090668452683,0.0,
         0.000376008102320, 0.014089835846691, 0.999900662638081, 0.0,
         0,0,0,1.000000000000000]
Camera.width: 512
Camera.height: 512
Camera.fps: 20
Camera.RGB: 1
Stereo.ThDepth: 40.0
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

TEST(Settings, OldStyleTumLoadsUnchanged) {
  TempDir dir;
  const Settings s = load_settings(dir.write("TUM1.yaml", kOldTum));
  EXPECT_DOUBLE_EQ(s.camera.fx, 517.306408);
  EXPECT_DOUBLE_EQ(s.camera.cy, 255.313989);
  ASSERT_EQ(s.camera.distortion.size(), 5u);
  EXPECT_DOUBLE_EQ(s.camera.distortion[0], 0.262383);
  EXPECT_DOUBLE_EQ(s.camera.distortion[4], 1.163314);
  EXPECT_EQ(s.camera.model, CameraModel::Pinhole);
  EXPECT_EQ(s.camera.width, 640);
  EXPECT_EQ(s.camera.height, 480);
  EXPECT_DOUBLE_EQ(s.bf, 40.0);
  EXPECT_DOUBLE_EQ(s.th_depth, 40.0);
  EXPECT_DOUBLE_EQ(s.depth_map_factor, 5000.0);
  EXPECT_DOUBLE_EQ(s.fps, 30.0);
  EXPECT_TRUE(s.rgb);
  EXPECT_FALSE(s.stereo.has_value());  // DepthMapFactor present: RGB-D
  EXPECT_NEAR(s.close_depth(), 40.0 * 40.0 / 517.306408, 1e-12);
  EXPECT_EQ(s.orb.n_features, 1000);
  EXPECT_FLOAT_EQ(s.orb.scale_factor, 1.2f);
  EXPECT_EQ(s.orb.n_levels, 8);
  EXPECT_EQ(s.orb.ini_th_fast, 20);
  EXPECT_EQ(s.orb.min_th_fast, 7);
  // No Segmentation keys: defaults, with the shipped model.
  EXPECT_TRUE(s.segmentation.enabled);
  EXPECT_EQ(s.segmentation.classes, std::vector<std::string>{"person"});
  EXPECT_EQ(std::filesystem::path(s.segmentation.model_path),
            (std::filesystem::absolute(STILLSLAM_SOURCE_DIR) / "models/yolo11n-seg_384x512.onnx").lexically_normal());
}

TEST(Settings, OldStyleStereoWithRectificationBlocks) {
  TempDir dir;
  const Settings s = load_settings(dir.write("EuRoC.yaml", kOldEuroc));
  EXPECT_DOUBLE_EQ(s.camera.fx, 435.2046959714599);
  EXPECT_TRUE(s.camera.distortion.empty());
  EXPECT_DOUBLE_EQ(s.bf, 47.90639384423901);
  EXPECT_DOUBLE_EQ(s.th_depth, 35.0);
  ASSERT_TRUE(s.stereo.has_value());
  EXPECT_FALSE(s.stereo->rectified);
  EXPECT_DOUBLE_EQ(s.stereo->left.fx, 458.654);
  EXPECT_DOUBLE_EQ(s.stereo->right.cx, 379.999);
  ASSERT_EQ(s.stereo->left.distortion.size(), 5u);
  EXPECT_DOUBLE_EQ(s.stereo->left.distortion[0], -0.28340811);
  EXPECT_EQ(s.stereo->left.width, 752);
  EXPECT_NEAR(s.stereo->baseline, 0.11007778, 1e-7);
  // T_c1_c2 recovered from the rectification matches the one from the EuRoC
  // body-frame extrinsics, inv(T_BS0) * T_BS1 = (0.110074, -0.000157, 0.000889).
  const Eigen::Vector3d t = s.stereo->T_c1_c2.translation();
  EXPECT_NEAR(t.x(), 0.110074, 2e-5);
  EXPECT_NEAR(t.y(), -0.000157, 2e-5);
  EXPECT_NEAR(t.z(), 0.000889, 2e-5);
  EXPECT_NEAR(s.stereo->T_c1_c2.linear()(1, 2), -0.014090668, 2e-5);
  EXPECT_NEAR(s.close_depth(), 35.0 * 0.11007778, 1e-5);
}

TEST(Settings, NewStyleRectifiedStereo) {
  TempDir dir;
  const Settings s = load_settings(dir.write("KITTI00-02.yaml", kNewKitti));
  EXPECT_DOUBLE_EQ(s.camera.fx, 718.856);
  EXPECT_EQ(s.camera.width, 1241);
  ASSERT_TRUE(s.stereo.has_value());
  EXPECT_TRUE(s.stereo->rectified);
  EXPECT_DOUBLE_EQ(s.stereo->baseline, 0.53716);
  EXPECT_DOUBLE_EQ(s.stereo->T_c1_c2.translation().x(), 0.53716);
  EXPECT_DOUBLE_EQ(s.stereo->right.fx, 718.856);
  EXPECT_NEAR(s.bf, 0.53716 * 718.856, 1e-9);
  EXPECT_DOUBLE_EQ(s.th_depth, 35.0);
  EXPECT_DOUBLE_EQ(s.fps, 10.0);
  EXPECT_EQ(s.orb.n_features, 2000);
  EXPECT_FALSE(s.stereo_flow_matching);
  const Settings flow = load_settings(dir.write("KITTI_flow.yaml", std::string(kNewKitti) + "Stereo.flowMatching: 1\n"));
  EXPECT_TRUE(flow.stereo_flow_matching);
}

TEST(Settings, NewStyleFisheyeStereo) {
  TempDir dir;
  const Settings s = load_settings(dir.write("TUM-VI.yaml", kNewFisheye));
  EXPECT_EQ(s.camera.model, CameraModel::KannalaBrandt8);
  ASSERT_EQ(s.camera.distortion.size(), 4u);
  EXPECT_DOUBLE_EQ(s.camera.distortion[3], 0.00020293673591811182);
  ASSERT_TRUE(s.stereo.has_value());
  EXPECT_FALSE(s.stereo->rectified);
  EXPECT_EQ(s.stereo->right.model, CameraModel::KannalaBrandt8);
  EXPECT_DOUBLE_EQ(s.stereo->right.fx, 190.44236969414825);
  EXPECT_NEAR(s.stereo->baseline, 0.101, 1e-6);  // |t| of T_c1_c2 (dt: f)
  EXPECT_NEAR(s.bf, 0.101 * 190.97847715128717, 1e-4);
}

TEST(Settings, SegmentationKeys) {
  TempDir dir;
  const std::string base = kOldTum;
  {
    const Settings s = load_settings(dir.write(
        "sub/a.yaml", base + "Segmentation.enabled: 0\nSegmentation.model: \"../models/m.onnx\"\n"
                             "Segmentation.classes: \"person, chair,dog\"\nSegmentation.scoreThreshold: 0.4\n"
                             "Segmentation.nmsIouThreshold: 0.5\nSegmentation.maskThreshold: 0.6\n"
                             "Segmentation.maskDilation: 7\nSegmentation.threads: 2\n"
                             "Segmentation.holdFrames: 4\n"
                             "Segmentation.masksForClassesOnly: 1\nSegmentation.agnosticNms: 1\n"));
    EXPECT_FALSE(s.segmentation.enabled);
    EXPECT_EQ(std::filesystem::path(s.segmentation.model_path),
              (std::filesystem::absolute(dir.path()) / "models/m.onnx").lexically_normal());
    EXPECT_EQ(s.segmentation.classes, (std::vector<std::string>{"person", "chair", "dog"}));
    EXPECT_FLOAT_EQ(s.segmentation.score_threshold, 0.4f);
    EXPECT_FLOAT_EQ(s.segmentation.nms_iou_threshold, 0.5f);
    EXPECT_FLOAT_EQ(s.segmentation.mask_threshold, 0.6f);
    EXPECT_EQ(s.segmentation.mask_dilation, 7);
    EXPECT_EQ(s.segmentation.hold_frames, 4);
    EXPECT_EQ(s.segmentation.threads, 2);
    EXPECT_TRUE(s.segmentation.masks_for_classes_only);
    EXPECT_TRUE(s.segmentation.agnostic_nms);
  }
  {
    const Settings s = load_settings(
        dir.write("b.yaml", base + "Segmentation.classes: [person, \"car\", 15]\n"
                                   "Segmentation.model: \"/abs/model.onnx\"\n"));
    EXPECT_EQ(s.segmentation.classes, (std::vector<std::string>{"person", "car", "15"}));
    EXPECT_EQ(s.segmentation.model_path, "/abs/model.onnx");
  }
  {  // nested map form
    const Settings s = load_settings(
        dir.write("c.yaml", base + "Segmentation:\n  enabled: 0\n  maskDilation: 3\n"));
    EXPECT_FALSE(s.segmentation.enabled);
    EXPECT_EQ(s.segmentation.mask_dilation, 3);
  }
}

TEST(Settings, ErrorsNameFileAndKey) {
  TempDir dir;
  const std::string tum = kOldTum;
  struct Case {
    std::string text, key, hint;
  };
  const std::vector<Case> cases = {
      {replaced(tum, "Camera.fx: 517.306408\n", ""), "Camera.fx", "missing"},
      {replaced(tum, "Camera.fy: 516.469215", "Camera.fy: -1"), "Camera.fy", "is -1: must be in [10, 100000]"},
      {replaced(tum, "Camera.fx: 517.306408", "Camera.fx: \"abc\""), "Camera.fx", "number"},
      {replaced(tum, "Camera.fps: 30.0", "Camera.type: \"Fisheye\""), "Camera.type", "KannalaBrandt8"},
      {replaced(tum, "ORBextractor.nFeatures: 1000", "ORBextractor.nFeatures: 0"), "ORBextractor.nFeatures",
       "is 0: must be in [100, 50000]"},
      {replaced(tum, "ORBextractor.scaleFactor: 1.2", "ORBextractor.scaleFactor: 1.0"),
       "ORBextractor.scaleFactor", "is 1: must be > 1"},
      {replaced(tum, "ORBextractor.minThFAST: 7", "ORBextractor.minThFAST: 25"), "ORBextractor.minThFAST",
       "is 25: must be in [1, 20]"},
      {replaced(tum, "ORBextractor.nLevels: 8", "ORBextractor.nLevels: 2.5"), "ORBextractor.nLevels",
       "must be an integer"},
      {replaced(tum, "DepthMapFactor: 5000.0", "DepthMapFactor: 0"), "DepthMapFactor", "is 0: must be in [1, 100000]"},
      {replaced(tum, "Camera.bf: 40.0", "Camera.bf: -40.0"), "Camera.bf", "is -40: must be in ["},
      {replaced(tum, "Camera.RGB: 1", "Camera.RGB: 2"), "Camera.RGB", "0 (BGR) or 1"},
      {tum + "Segmentation.scoreTreshold: 0.3\n", "Segmentation.scoreTreshold",
       "known keys: Segmentation.enabled, Segmentation.model, Segmentation.classes, "
       "Segmentation.scoreThreshold"},
      {tum + "Segmentation.scoreThreshold: 1.5\n", "Segmentation.scoreThreshold", "is 1.5: must be in [0, 1]"},
      {tum + "Segmentation.maskThreshold: 1\n", "Segmentation.maskThreshold", "is 1: must be in (0, 1)"},
      {tum + "Segmentation.holdFrames: -1\n", "Segmentation.holdFrames", "is -1: must be in [0, 1000]"},
      {tum + "Segmentation.enabled: 2\n", "Segmentation.enabled", "must be 0 or 1"},
      {tum + "Segmentation.model: 3\n", "Segmentation.model", "non-empty path"},
      {tum + "Segmentation: 3\n", "Segmentation", "must be a map"},
      {tum + "Segmentation.classes: \"\"\n", "Segmentation.classes", "empty"},
      {tum + "Segmentation:\n  treads: 2\n", "Segmentation.treads", "known keys"},
      {replaced(kNewKitti, "Stereo.b: 0.53716\n", ""), "Stereo.b", "Rectified"},
      {std::string(kNewKitti) + "Stereo.flowMatching: 2\n", "Stereo.flowMatching", "0 (descriptor matches only)"},
      {replaced(kNewKitti, "Stereo.b: 0.53716", "Stereo.b: 0"), "Stereo.b", "is 0: must be in [0.001, 10]"},
      {replaced(kNewKitti, "File.version: \"1.0\"", "File.version: \"2.0\""), "File.version", "1.0"},
      {replaced(kNewFisheye, "Stereo.T_c1_c2", "Stereo.T_c2_c1"), "Stereo.T_c1_c2", "missing"},
      {replaced(kNewFisheye, "Camera2.k4: 0.0003299517423931039\n", ""), "Camera2.k4", "missing"},
      {replaced(kNewFisheye, "rows: 4\n  cols: 4", "rows: 2\n  cols: 8"), "Stereo.T_c1_c2", "4x4"},
  };
  for (const Case& c : cases) {
    const std::string message = test::settings_error(dir, c.text);
    SCOPED_TRACE(c.key);
    EXPECT_NE(message.find("bad.yaml"), std::string::npos) << message;
    EXPECT_NE(message.find("'" + c.key + "'"), std::string::npos) << message;
    EXPECT_NE(message.find(c.hint), std::string::npos) << message;
  }
}

// ORB-SLAM3's Stereo-Inertial/EuRoC.yaml has a matrix row without its
// trailing comma, which OpenCV 4 rejects; it must still load.
TEST(Settings, MatrixRowWithoutComma) {
  TempDir dir;
  const std::string text = replaced(kOldEuroc, "ThDepth: 35\n",
                                    "ThDepth: 35.0 # 35\n"
                                    "Tbc: !!opencv-matrix\n   rows: 4\n   cols: 4\n   dt: f\n"
                                    "   data: [1.0, 0.0, 0.0, 0.0\n          0.0,-1.0, 0.0, 0.0,\n"
                                    "          0.0, 0.0,-1.0, 0.0,\n          0.0, 0.0, 0.0, 1.0]\n"
                                    "IMU.NoiseGyro: 1.7e-04 # 1.6968e-04 \n");
  const Settings s = load_settings(dir.write("EuRoC-inertial.yaml", text));
  EXPECT_DOUBLE_EQ(s.bf, 47.90639384423901);
  ASSERT_TRUE(s.stereo.has_value());
  EXPECT_NEAR(s.stereo->baseline, 0.11007778, 1e-7);
}

TEST(Settings, MissingOrMalformedFile) {
  TempDir dir;
  try {
    load_settings(dir.path() / "nope.yaml");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("nope.yaml: settings file not found"), std::string::npos) << e.what();
  }
  const std::string message = test::settings_error(dir, "%YAML:1.0\nCamera.fx: [1, 2\nCamera.fy: 3\n");
  EXPECT_NE(message.find("bad.yaml"), std::string::npos) << message;
  EXPECT_NE(message.find("YAML"), std::string::npos) << message;
}

std::filesystem::path preset(const std::string& name) {
  return std::filesystem::path(STILLSLAM_SOURCE_DIR) / "config" / name;
}

void expect_preset_segmentation(const Settings& s) {
  EXPECT_TRUE(s.segmentation.enabled);
  EXPECT_EQ(std::filesystem::path(s.segmentation.model_path),
            (std::filesystem::absolute(std::filesystem::path(STILLSLAM_SOURCE_DIR)) /
             "models/yolo11n-seg_384x512.onnx")
                .lexically_normal());
  EXPECT_EQ(s.segmentation.classes, std::vector<std::string>{"person"});
}

TEST(SettingsPresets, Tum) {
  const Settings fr1 = load_settings(preset("tum_fr1.yaml"));
  EXPECT_DOUBLE_EQ(fr1.camera.fx, 517.306408);
  EXPECT_EQ(fr1.camera.distortion.size(), 5u);
  EXPECT_DOUBLE_EQ(fr1.depth_map_factor, 5000.0);
  EXPECT_NEAR(fr1.bf, 40.0, 0.01);
  EXPECT_FALSE(fr1.stereo.has_value());
  expect_preset_segmentation(fr1);

  const Settings fr2 = load_settings(preset("tum_fr2.yaml"));
  EXPECT_DOUBLE_EQ(fr2.camera.cx, 325.141442);
  EXPECT_DOUBLE_EQ(fr2.depth_map_factor, 5208.0);
  EXPECT_NEAR(fr2.bf, 40.0, 0.01);
  expect_preset_segmentation(fr2);

  const Settings fr3 = load_settings(preset("tum_fr3.yaml"));
  EXPECT_DOUBLE_EQ(fr3.camera.fx, 535.4);
  EXPECT_DOUBLE_EQ(fr3.camera.fy, 539.2);
  EXPECT_TRUE(fr3.camera.distortion.empty());  // fr3 is undistorted
  EXPECT_NEAR(fr3.close_depth(), 40.0 * 0.0747, 1e-9);
  EXPECT_FALSE(fr3.stereo.has_value());
  expect_preset_segmentation(fr3);
}

TEST(SettingsPresets, Euroc) {
  const Settings s = load_settings(preset("euroc.yaml"));
  ASSERT_TRUE(s.stereo.has_value());
  EXPECT_FALSE(s.stereo->rectified);
  EXPECT_DOUBLE_EQ(s.stereo->left.fx, 458.654);
  EXPECT_DOUBLE_EQ(s.stereo->right.fx, 457.587);
  EXPECT_EQ(s.stereo->right.distortion.size(), 4u);
  EXPECT_NEAR(s.stereo->baseline, 0.1100778, 1e-6);
  EXPECT_NEAR(s.bf, 0.1100778 * 458.654, 1e-3);
  EXPECT_DOUBLE_EQ(s.fps, 20.0);
  EXPECT_EQ(s.orb.n_features, 1200);
  expect_preset_segmentation(s);
}

TEST(SettingsPresets, Kitti) {
  struct Expected {
    const char* file;
    double fx, bf;
    int width, ini_th;
  };
  for (const Expected& e : {Expected{"kitti_00-02.yaml", 718.856, 386.1448, 1241, 20},
                            Expected{"kitti_03.yaml", 721.5377, 387.5744, 1242, 20},
                            Expected{"kitti_04-12.yaml", 707.0912, 379.8145, 1226, 12}}) {
    SCOPED_TRACE(e.file);
    const Settings s = load_settings(preset(e.file));
    EXPECT_DOUBLE_EQ(s.camera.fx, e.fx);
    EXPECT_NEAR(s.bf, e.bf, 1e-9);
    EXPECT_EQ(s.camera.width, e.width);
    ASSERT_TRUE(s.stereo.has_value());
    EXPECT_TRUE(s.stereo->rectified);
    EXPECT_NEAR(s.stereo->baseline, 0.5371, 1e-4);
    EXPECT_EQ(s.orb.n_features, 2000);
    EXPECT_EQ(s.orb.ini_th_fast, e.ini_th);
    expect_preset_segmentation(s);
  }
}

}  // namespace
}  // namespace stillslam
