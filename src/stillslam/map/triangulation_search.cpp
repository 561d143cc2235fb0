#include "stillslam/map/triangulation_search.h"

#include <algorithm>
#include <cmath>

#include "stillslam/features/descriptor.h"
#include "stillslam/features/descriptor_matcher.h"
#include "stillslam/geometry/se3.h"
#include "stillslam/map/matching_thresholds.h"

namespace stillslam {

namespace {

// Squared distance (pixels^2) of pixel x2 to the epipolar line l = F21 * x1.
double epipolar_distance2(const Eigen::Matrix3d& F21, const Eigen::Vector2d& x1,
                          const Eigen::Vector2d& x2) {
  const Eigen::Vector3d l = F21 * Eigen::Vector3d(x1.x(), x1.y(), 1.0);
  const double num = l.x() * x2.x() + l.y() * x2.y() + l.z();
  const double den = l.x() * l.x() + l.y() * l.y();
  return den > 0 ? num * num / den : 1e12;
}

}  // namespace

std::vector<std::pair<std::size_t, std::size_t>> search_for_triangulation(
    const KeyFrame& kf1, const KeyFrame& kf2, const TriangulationSearchOptions& options) {
  const CameraSetup& setup = kf1.setup();
  const PinholeCamera& camera = setup.camera;
  const Eigen::Isometry3d T_21 = kf2.T_cam_world() * kf1.T_world_cam();
  // F21 = K^-T [t21]x R21 K^-1.
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  K(0, 0) = camera.fx();
  K(1, 1) = camera.fy();
  K(0, 2) = camera.cx();
  K(1, 2) = camera.cy();
  const Eigen::Matrix3d K_inv = K.inverse();
  const Eigen::Matrix3d F21 = K_inv.transpose() * skew(T_21.translation()) * T_21.linear() * K_inv;

  std::vector<char> taken2(kf2.size(), 0);
  std::vector<std::pair<std::size_t, std::size_t>> matches;
  std::vector<float> angle_differences;
  // Grid hits of the samples along the epipolar segment, sorted and unique
  // (a reused buffer: the windows of neighbouring samples overlap).
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < kf1.size(); ++i) {
    if (kf1.map_point(i)) continue;
    const cv::KeyPoint& kp1 = kf1.keypoint(i);
    const Eigen::Vector2d x1(kp1.pt.x, kp1.pt.y);
    double near = options.min_depth, far = options.max_depth;
    const float z1 = kf1.depth(i);
    if (z1 > 0) {
      near = z1 * (1.0 - options.depth_margin);
      far = z1 * (1.0 + options.depth_margin);
    }
    // Ray end points in camera 2; clip the near end to the front of camera 2.
    Eigen::Vector3d a = T_21 * camera.unproject(x1, near);
    Eigen::Vector3d b = T_21 * camera.unproject(x1, far);
    constexpr double kMinZ = 0.05;
    if (a.z() < kMinZ && b.z() < kMinZ) continue;
    if (a.z() < kMinZ) a = a + (b - a) * ((kMinZ - a.z()) / (b.z() - a.z()));
    if (b.z() < kMinZ) b = b + (a - b) * ((kMinZ - b.z()) / (a.z() - b.z()));
    const Eigen::Vector2d pa = camera.project(a), pb = camera.project(b);
    const float radius = options.window * setup.pyramid.scale[static_cast<std::size_t>(kp1.octave)];
    const double length = (pb - pa).norm();
    // Sample the segment every `radius` pixels (capped) and gather grid hits.
    const int steps = std::min(200, static_cast<int>(std::ceil(length / radius)));
    candidates.clear();
    for (int s = 0; s <= steps; ++s) {
      const Eigen::Vector2d p = steps == 0 ? pa : Eigen::Vector2d(pa + (pb - pa) * (double(s) / steps));
      if (!camera.in_image(p)) continue;
      for (std::size_t j : kf2.features_in_area(static_cast<float>(p.x()), static_cast<float>(p.y()), radius,
                                                std::max(kp1.octave - 2, 0), kp1.octave + 2)) {
        candidates.push_back(j);
      }
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    int best_distance = kDescriptorDistanceLow + 1;
    std::ptrdiff_t best = -1;
    for (std::size_t j : candidates) {
      if (taken2[j] || kf2.map_point(j)) continue;
      const int d = descriptor_distance(kf1.descriptor(i), kf2.descriptor(j));
      if (d >= best_distance) continue;
      const cv::KeyPoint& kp2 = kf2.keypoint(j);
      const double sigma2 = setup.pyramid.sigma2[static_cast<std::size_t>(kp2.octave)];
      if (epipolar_distance2(F21, x1, Eigen::Vector2d(kp2.pt.x, kp2.pt.y)) > 3.84 * sigma2) continue;
      best_distance = d;
      best = static_cast<std::ptrdiff_t>(j);
    }
    if (best < 0) continue;
    const auto j = static_cast<std::size_t>(best);
    taken2[j] = 1;
    matches.emplace_back(i, j);
    angle_differences.push_back(kf2.keypoint(j).angle - kp1.angle);
  }
  if (!options.check_orientation || matches.empty()) return matches;
  const std::vector<bool> keep = rotation_consistent(angle_differences);
  std::vector<std::pair<std::size_t, std::size_t>> kept;
  for (std::size_t k = 0; k < matches.size(); ++k) {
    if (keep[k]) kept.push_back(matches[k]);
  }
  return kept;
}

}  // namespace stillslam
