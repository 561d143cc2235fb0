#include "stillslam/map/map_file_checks.h"

#include <Eigen/LU>
#include <cmath>
#include <sstream>

namespace stillslam::map_file_checks {

namespace {

// Rotations are saved as 9 doubles from an orthonormalized matrix: far below
// this after any number of pose updates, far above for a changed entry.
constexpr double kRotationTolerance = 1e-6;
// Beyond any real scene, in metres; a changed exponent lands far past it.
constexpr double kMaxCoordinate = 1e7;

std::string text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

Problem pose(const Eigen::Matrix<double, 3, 4>& T) {
  if (!T.allFinite()) return "pose has a non-finite entry";
  const Eigen::Matrix3d R = T.leftCols<3>();
  const double off = (R * R.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (off > kRotationTolerance || R.determinant() < 0) {
    return "pose rotation is not a rotation (|R R^T - I| = " + text(off) + ", det " + text(R.determinant()) + ")";
  }
  if (T.col(3).cwiseAbs().maxCoeff() > kMaxCoordinate) return "pose translation " + text(T.col(3).norm()) + " m";
  return std::nullopt;
}

Problem keypoint(const cv::KeyPoint& kp, int levels) {
  if (!std::isfinite(kp.pt.x) || !std::isfinite(kp.pt.y) || std::abs(kp.pt.x) > kMaxCoordinate ||
      std::abs(kp.pt.y) > kMaxCoordinate) {
    return "keypoint at (" + text(kp.pt.x) + ", " + text(kp.pt.y) + ")";
  }
  if (!std::isfinite(kp.size) || kp.size <= 0) return "keypoint size " + text(kp.size);
  if (!std::isfinite(kp.angle) || kp.angle < -1 || kp.angle > 360) return "keypoint angle " + text(kp.angle);
  if (!std::isfinite(kp.response)) return "keypoint response " + text(kp.response);
  if (kp.octave < 0 || kp.octave >= levels) {
    return "keypoint octave " + std::to_string(kp.octave) + " outside the " + std::to_string(levels) + " levels";
  }
  return std::nullopt;
}

Problem stereo(float u_right, float depth) {
  if (!std::isfinite(u_right)) return "right coordinate " + text(u_right);
  if (!std::isfinite(depth) || depth > kMaxCoordinate) return "depth " + text(depth);
  return std::nullopt;
}

Problem point(const Eigen::Vector3d& position, const Eigen::Vector3d& normal, double min_distance,
              double max_distance, int visible, int found) {
  if (!position.allFinite() || position.cwiseAbs().maxCoeff() > kMaxCoordinate) {
    return "position (" + text(position.x()) + ", " + text(position.y()) + ", " + text(position.z()) + ")";
  }
  const double n = normal.norm();
  if (!normal.allFinite() || (n != 0 && std::abs(n - 1) > 1e-6)) return "normal of length " + text(n);
  if (!std::isfinite(min_distance) || !std::isfinite(max_distance) || min_distance < 0 ||
      min_distance > max_distance || max_distance > kMaxCoordinate) {
    return "distance range [" + text(min_distance) + ", " + text(max_distance) + "]";
  }
  if (visible < 0 || found < 0) {
    return "visible/found counts " + std::to_string(visible) + "/" + std::to_string(found);
  }
  return std::nullopt;
}

}  // namespace stillslam::map_file_checks
