#include "stillslam/io/camera_settings.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "stillslam/core/error.h"
#include "stillslam/core/option_check.h"
#include "stillslam/core/text.h"
#include "stillslam/io/distortion_check.h"
#include "stillslam/io/yaml_reader.h"

namespace stillslam {
namespace {

// What a real camera can be. Wide enough for any lens and sensor in use
// (a 100 px fisheye focal length to a telephoto on a 20000 px sensor);
// outside, a number is a typo or a unit mix-up and every result from it
// would be nonsense.
constexpr double kMinFocal = 10, kMaxFocal = 100000;  // pixels
constexpr int kMinSize = 16, kMaxSize = 20000;         // image width, height in pixels
constexpr double kMinFps = 0.1, kMaxFps = 1000;
constexpr double kMinBaseline = 0.001, kMaxBaseline = 10;  // metres
constexpr double kMinThDepth = 1, kMaxThDepth = 1000;      // baselines
constexpr double kMinDepthFactor = 1, kMaxDepthFactor = 100000;  // depth units per metre (1000: mm, 5000: TUM)

// "key 'X' is V: must be in [min, max] (what)" for a value out of range.
void require_range(const YamlReader& yaml, const std::string& key, double value, double min, double max,
                   const std::string& what) {
  if (value >= min && value <= max) return;
  yaml.fail(key, "is " + option_check::text(value) + ": must be in [" + option_check::text(min) + ", " +
                     option_check::text(max) + "] (" + what + ")");
}

// Focal lengths, principal point (inside the image when its size is known)
// and a distortion that does not fold the image. `keys` maps the fields to
// the file's keys, e.g. {"Camera1.fx", ...}.
struct CameraKeys {
  std::string fx, fy, cx, cy, distortion;  // `distortion`: the coefficient keys' prefix, or a matrix key
  std::vector<std::string> coefficients;   // per coefficient, in CameraCalibration order
};

void check_camera(const YamlReader& yaml, const CameraCalibration& cam, const CameraKeys& keys) {
  require_range(yaml, keys.fx, cam.fx, kMinFocal, kMaxFocal, "focal length in pixels");
  require_range(yaml, keys.fy, cam.fy, kMinFocal, kMaxFocal, "focal length in pixels");
  const double width = cam.width > 0 ? cam.width : kMaxSize;
  const double height = cam.height > 0 ? cam.height : kMaxSize;
  const std::string inside = cam.width > 0 ? "principal point inside the image" : "principal point in pixels";
  require_range(yaml, keys.cx, cam.cx, 0, width, inside);
  require_range(yaml, keys.cy, cam.cy, 0, height, inside);
  const auto fold = distortion_fold(cam);
  if (!fold) return;
  // Name the coefficient that makes the fold: the first whose removal ends it.
  for (std::size_t i = 0; i < cam.distortion.size() && i < keys.coefficients.size(); ++i) {
    CameraCalibration without = cam;
    without.distortion[i] = 0;
    if (distortion_fold(without)) continue;
    yaml.fail(keys.coefficients[i], "is " + option_check::text(cam.distortion[i]) +
                                        ": this distortion folds the image " + *fold +
                                        " (two directions land on one pixel); check the calibration's "
                                        "coefficients and their order (k1 k2 p1 p2 [k3])");
  }
  yaml.fail(keys.distortion, "folds the image " + *fold +
                                 " (two directions land on one pixel); check the calibration's coefficients");
}

enum class CameraType { PinHole, KannalaBrandt8, Rectified };

CameraType read_camera_type(const YamlReader& yaml) {
  const auto type = yaml.optional_string("Camera.type");
  if (!type) return CameraType::PinHole;  // ORB-SLAM2 files have no Camera.type
  const std::string t = lower(*type);
  if (t == "pinhole") return CameraType::PinHole;
  if (t == "kannalabrandt8") return CameraType::KannalaBrandt8;
  if (t == "rectified") return CameraType::Rectified;
  yaml.fail("Camera.type", "has unknown value '" + *type +
                               "' (use \"PinHole\", \"KannalaBrandt8\" or \"Rectified\")");
}

// Reads fx..cy and the distortion of one camera; `prefix` is "Camera.",
// "Camera1." or "Camera2.".
CameraCalibration read_camera(const YamlReader& yaml, const std::string& prefix, CameraType type) {
  CameraCalibration cam;
  cam.model = type == CameraType::KannalaBrandt8 ? CameraModel::KannalaBrandt8 : CameraModel::Pinhole;
  cam.fx = yaml.number(prefix + "fx");
  cam.fy = yaml.number(prefix + "fy");
  cam.cx = yaml.number(prefix + "cx");
  cam.cy = yaml.number(prefix + "cy");
  if (type == CameraType::KannalaBrandt8) {
    for (const char* k : {"k1", "k2", "k3", "k4"}) cam.distortion.push_back(yaml.number(prefix + k));
  } else if (type == CameraType::PinHole && yaml.has(prefix + "k1")) {
    // As ORB-SLAM3: k1 present means k2 p1 p2 are required, k3 optional.
    for (const char* k : {"k1", "k2", "p1", "p2"}) cam.distortion.push_back(yaml.number(prefix + k));
    if (const auto k3 = yaml.optional_number(prefix + "k3")) cam.distortion.push_back(*k3);
  }
  // All-zero coefficients mean "no distortion": keep one representation.
  if (std::all_of(cam.distortion.begin(), cam.distortion.end(), [](double d) { return d == 0.0; })) {
    cam.distortion.clear();
  }
  cam.width = yaml.optional_integer("Camera.width").value_or(0);
  cam.height = yaml.optional_integer("Camera.height").value_or(0);
  if (yaml.has("Camera.width")) require_range(yaml, "Camera.width", cam.width, kMinSize, kMaxSize, "pixels");
  if (yaml.has("Camera.height")) require_range(yaml, "Camera.height", cam.height, kMinSize, kMaxSize, "pixels");
  CameraKeys keys{prefix + "fx", prefix + "fy", prefix + "cx", prefix + "cy", prefix + "k1", {}};
  for (const char* k : type == CameraType::KannalaBrandt8 ? std::vector<const char*>{"k1", "k2", "k3", "k4"}
                                                         : std::vector<const char*>{"k1", "k2", "p1", "p2", "k3"}) {
    keys.coefficients.push_back(prefix + k);
  }
  check_camera(yaml, cam, keys);
  return cam;
}

Eigen::Isometry3d read_pose(const YamlReader& yaml, const std::string& key) {
  const auto m = yaml.optional_matrix(key);
  if (!m) yaml.fail(key, "is missing (required: 4x4 transform of camera 2 in camera 1)");
  if (m->rows() != 4 || m->cols() != 4) yaml.fail(key, "must be a 4x4 matrix");
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = m->topLeftCorner<3, 3>();
  T.translation() = m->topRightCorner<3, 1>();
  const double ortho_error = (T.linear() * T.linear().transpose() - Eigen::Matrix3d::Identity()).norm();
  if (ortho_error > 1e-3) yaml.fail(key, "has a rotation part that is not a rotation matrix");
  return T;
}

// Old-style stereo files (ORB-SLAM2 EuRoC.yaml) describe the raw cameras and
// their rectification as LEFT.K/D/R/P and RIGHT.K/D/R/P. The rectified frames
// differ by a pure x translation, so T_c1_c2 = R1^T [R2 | (b,0,0)].
StereoCalibration read_left_right_blocks(const YamlReader& yaml) {
  auto matrix = [&](const std::string& key, int rows, int cols) {
    const auto m = yaml.optional_matrix(key);
    if (!m) yaml.fail(key, "is missing (LEFT.* and RIGHT.* blocks must be complete)");
    if (m->rows() != rows || m->cols() != cols) {
      yaml.fail(key, "must be " + std::to_string(rows) + "x" + std::to_string(cols));
    }
    return *m;
  };
  auto raw_camera = [&](const std::string& side) {
    CameraCalibration cam;
    const Eigen::MatrixXd K = matrix(side + ".K", 3, 3);
    cam.fx = K(0, 0);
    cam.fy = K(1, 1);
    cam.cx = K(0, 2);
    cam.cy = K(1, 2);
    const auto D = yaml.optional_matrix(side + ".D");
    if (!D) yaml.fail(side + ".D", "is missing (distortion k1 k2 p1 p2 [k3])");
    for (Eigen::Index i = 0; i < D->size(); ++i) cam.distortion.push_back(D->data()[i]);
    if (std::all_of(cam.distortion.begin(), cam.distortion.end(), [](double d) { return d == 0.0; })) {
      cam.distortion.clear();
    }
    cam.width = yaml.optional_integer(side + ".width").value_or(0);
    cam.height = yaml.optional_integer(side + ".height").value_or(0);
    if (yaml.has(side + ".width")) require_range(yaml, side + ".width", cam.width, kMinSize, kMaxSize, "pixels");
    if (yaml.has(side + ".height")) require_range(yaml, side + ".height", cam.height, kMinSize, kMaxSize, "pixels");
    const std::string k = side + ".K";
    check_camera(yaml, cam, {k + " fx (0,0)", k + " fy (1,1)", k + " cx (0,2)", k + " cy (1,2)", side + ".D",
                             {side + ".D k1", side + ".D k2", side + ".D p1", side + ".D p2", side + ".D k3"}});
    return cam;
  };
  StereoCalibration stereo;
  stereo.left = raw_camera("LEFT");
  stereo.right = raw_camera("RIGHT");
  const Eigen::Matrix3d R1 = matrix("LEFT.R", 3, 3);
  const Eigen::Matrix3d R2 = matrix("RIGHT.R", 3, 3);
  const Eigen::MatrixXd P2 = matrix("RIGHT.P", 3, 4);
  if (P2(0, 0) <= 0 || P2(0, 3) >= 0) {
    yaml.fail("RIGHT.P", "must be a rectified projection with P(0,3) = -fx * baseline < 0");
  }
  stereo.baseline = -P2(0, 3) / P2(0, 0);
  require_range(yaml, "RIGHT.P", stereo.baseline, kMinBaseline, kMaxBaseline,
                "the baseline -P(0,3) / P(0,0), metres");
  stereo.T_c1_c2.linear() = R1.transpose() * R2;
  stereo.T_c1_c2.translation() = R1.transpose() * Eigen::Vector3d(stereo.baseline, 0, 0);
  stereo.rectified = false;
  return stereo;
}

StereoCalibration rectified_pair(const CameraCalibration& camera, double baseline) {
  StereoCalibration stereo;
  stereo.left = camera;
  stereo.left.distortion.clear();
  stereo.right = stereo.left;
  stereo.T_c1_c2.translation() = Eigen::Vector3d(baseline, 0, 0);
  stereo.baseline = baseline;
  stereo.rectified = true;
  return stereo;
}

std::optional<double> first_number(const YamlReader& yaml, std::initializer_list<const char*> keys,
                                   std::string* found = nullptr) {
  for (const char* key : keys) {
    if (const auto v = yaml.optional_number(key)) {
      if (found) *found = key;
      return v;
    }
  }
  return std::nullopt;
}

void read_camera_section(const YamlReader& yaml, CameraSettings& s) {
  const CameraType type = read_camera_type(yaml);
  std::string prefix = "Camera.";
  if (const auto version = yaml.optional_string("File.version")) {
    if (*version != "1.0") yaml.fail("File.version", "must be \"1.0\" (the only new-style version)");
    prefix = "Camera1.";
  } else if (yaml.has("Camera1.fx") && !yaml.has("Camera.fx")) {
    prefix = "Camera1.";  // new-style keys without File.version: accept them
  }
  if (!yaml.has(prefix + "fx")) {
    yaml.fail(prefix + "fx", prefix == "Camera1."
                                 ? "is missing (new-style files with File.version \"1.0\" use Camera1.fx..cy)"
                                 : "is missing (old-style files use Camera.fx..cy; new style: File.version "
                                   "\"1.0\" and Camera1.fx..cy)");
  }
  s.camera = read_camera(yaml, prefix, type);
  s.fps = yaml.optional_number("Camera.fps").value_or(s.fps);
  require_range(yaml, "Camera.fps", s.fps, kMinFps, kMaxFps, "frames per second");
  if (const auto rgb = yaml.optional_integer("Camera.RGB")) {
    if (*rgb != 0 && *rgb != 1) yaml.fail("Camera.RGB", "must be 0 (BGR) or 1 (RGB)");
    s.rgb = *rgb == 1;
  }
  std::string th_key;
  s.th_depth = first_number(yaml, {"Stereo.ThDepth", "ThDepth"}, &th_key).value_or(s.th_depth);
  if (!th_key.empty()) {
    require_range(yaml, th_key, s.th_depth, kMinThDepth, kMaxThDepth, "close/far threshold in baselines");
  }
  std::string depth_key;
  const auto depth_factor = first_number(yaml, {"RGBD.DepthMapFactor", "DepthMapFactor"}, &depth_key);
  if (depth_factor) {
    require_range(yaml, depth_key, *depth_factor, kMinDepthFactor, kMaxDepthFactor,
                  "depth image units per metre: 5000 for TUM, 1000 for millimetres");
    s.depth_map_factor = *depth_factor;
  }

  // Baseline: Stereo.b (metres) or Camera.bf (baseline * fx).
  std::optional<double> baseline;
  if (const auto b = yaml.optional_number("Stereo.b")) {
    require_range(yaml, "Stereo.b", *b, kMinBaseline, kMaxBaseline, "stereo baseline in metres");
    baseline = *b;
  } else if (const auto bf = yaml.optional_number("Camera.bf")) {
    require_range(yaml, "Camera.bf", *bf, kMinBaseline * s.camera.fx, kMaxBaseline * s.camera.fx,
                  "baseline in metres times fx: a baseline of " + option_check::text(kMinBaseline) + " to " +
                      option_check::text(kMaxBaseline) + " m");
    baseline = *bf / s.camera.fx;
  }

  const std::string prefix2 = prefix == "Camera1." ? "Camera2." : "";
  if (!prefix2.empty() && yaml.has("Camera2.fx") && type != CameraType::Rectified) {
    StereoCalibration stereo;
    stereo.left = s.camera;
    stereo.right = read_camera(yaml, prefix2, type);
    stereo.T_c1_c2 = read_pose(yaml, "Stereo.T_c1_c2");
    stereo.baseline = stereo.T_c1_c2.translation().norm();
    require_range(yaml, "Stereo.T_c1_c2", stereo.baseline, kMinBaseline, kMaxBaseline,
                  "the length of its translation, the baseline in metres");
    if (!baseline) baseline = stereo.baseline;
    s.stereo = stereo;
  } else if (prefix2.empty() && yaml.has("LEFT.K")) {
    s.stereo = read_left_right_blocks(yaml);
    if (!baseline) baseline = s.stereo->baseline;
  } else if (type == CameraType::Rectified) {
    if (!baseline) yaml.fail("Stereo.b", "is missing (required for Camera.type \"Rectified\")");
    s.stereo = rectified_pair(s.camera, *baseline);
  } else if (baseline && !depth_factor) {
    // A baseline without a depth factor is a rectified stereo pair (KITTI,
    // EuRoC rectified); RGB-D files always give DepthMapFactor.
    s.stereo = rectified_pair(s.camera, *baseline);
  }
  if (baseline) s.bf = *baseline * s.camera.fx;
  s.rgbd = depth_factor.has_value() && !s.stereo;
}

}  // namespace

double CameraSettings::baseline() const { return camera.fx > 0 ? bf / camera.fx : 0.0; }

double CameraSettings::close_depth() const { return th_depth * baseline(); }

CameraSettings read_camera_settings(const YamlReader& yaml) {
  CameraSettings s;
  s.file = yaml.file();
  read_camera_section(yaml, s);
  return s;
}

CameraSettings load_camera_settings(const std::filesystem::path& yaml_file) {
  return read_camera_settings(YamlReader(yaml_file));
}

}  // namespace stillslam
