#include "stillslam/io/camera_settings.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "stillslam/core/error.h"
#include "stillslam/core/text.h"
#include "stillslam/io/yaml_reader.h"

namespace stillslam {
namespace {

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
  if (cam.fx <= 0) yaml.fail(prefix + "fx", "must be positive (focal length in pixels)");
  if (cam.fy <= 0) yaml.fail(prefix + "fy", "must be positive (focal length in pixels)");
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
  if (cam.width < 0) yaml.fail("Camera.width", "must be positive");
  if (cam.height < 0) yaml.fail("Camera.height", "must be positive");
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
    if (cam.fx <= 0 || cam.fy <= 0) yaml.fail(side + ".K", "must have positive focal lengths");
    const auto D = yaml.optional_matrix(side + ".D");
    if (!D) yaml.fail(side + ".D", "is missing (distortion k1 k2 p1 p2 [k3])");
    for (Eigen::Index i = 0; i < D->size(); ++i) cam.distortion.push_back(D->data()[i]);
    if (std::all_of(cam.distortion.begin(), cam.distortion.end(), [](double d) { return d == 0.0; })) {
      cam.distortion.clear();
    }
    cam.width = yaml.optional_integer(side + ".width").value_or(0);
    cam.height = yaml.optional_integer(side + ".height").value_or(0);
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
  // Bounded: Tracking's keyframe spacing defaults to one second of frames (an int).
  if (!(s.fps > 0 && s.fps <= 1000)) yaml.fail("Camera.fps", "must be in (0, 1000] frames per second");
  if (const auto rgb = yaml.optional_integer("Camera.RGB")) {
    if (*rgb != 0 && *rgb != 1) yaml.fail("Camera.RGB", "must be 0 (BGR) or 1 (RGB)");
    s.rgb = *rgb == 1;
  }
  std::string th_key;
  s.th_depth = first_number(yaml, {"Stereo.ThDepth", "ThDepth"}, &th_key).value_or(s.th_depth);
  if (s.th_depth <= 0) yaml.fail(th_key, "must be positive (close/far threshold in baselines)");
  std::string depth_key;
  const auto depth_factor = first_number(yaml, {"RGBD.DepthMapFactor", "DepthMapFactor"}, &depth_key);
  if (depth_factor) {
    if (*depth_factor <= 0) {
      yaml.fail(depth_key, "must be positive (depth image units per metre, 5000 for TUM)");
    }
    s.depth_map_factor = *depth_factor;
  }

  // Baseline: Stereo.b (metres) or Camera.bf (baseline * fx).
  std::optional<double> baseline;
  if (const auto b = yaml.optional_number("Stereo.b")) {
    if (*b <= 0) yaml.fail("Stereo.b", "must be positive (stereo baseline in metres)");
    baseline = *b;
  } else if (const auto bf = yaml.optional_number("Camera.bf")) {
    if (*bf <= 0) yaml.fail("Camera.bf", "must be positive (baseline in metres times fx)");
    baseline = *bf / s.camera.fx;
  }

  const std::string prefix2 = prefix == "Camera1." ? "Camera2." : "";
  if (!prefix2.empty() && yaml.has("Camera2.fx") && type != CameraType::Rectified) {
    StereoCalibration stereo;
    stereo.left = s.camera;
    stereo.right = read_camera(yaml, prefix2, type);
    stereo.T_c1_c2 = read_pose(yaml, "Stereo.T_c1_c2");
    stereo.baseline = stereo.T_c1_c2.translation().norm();
    if (stereo.baseline <= 0) yaml.fail("Stereo.T_c1_c2", "must have a non-zero translation (the baseline)");
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
