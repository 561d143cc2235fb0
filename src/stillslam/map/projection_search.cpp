#include "stillslam/map/projection_search.h"

#include <cmath>

#include "stillslam/features/descriptor.h"
#include "stillslam/features/descriptor_matcher.h"
#include "stillslam/map/matching_thresholds.h"

namespace stillslam {

std::optional<ProjectedPoint> project_in_frustum(const Frame& frame, const MapPointPtr& point,
                                                 double min_view_cos) {
  const CameraSetup& setup = frame.setup();
  const Eigen::Vector3d& p_world = point->position();
  const Eigen::Vector3d p_cam = frame.T_cam_world() * p_world;
  if (p_cam.z() <= 0) return std::nullopt;
  const Eigen::Vector2d pixel = setup.camera.project(p_cam);
  if (!setup.camera.in_image(pixel)) return std::nullopt;
  const Eigen::Vector3d ray = p_world - frame.camera_center();
  const double distance = ray.norm();
  if (distance < point->min_distance() || distance > point->max_distance()) return std::nullopt;
  const double view_cos = ray.dot(point->normal()) / distance;
  if (view_cos < min_view_cos) return std::nullopt;
  ProjectedPoint out;
  out.point = point;
  out.pixel = pixel;
  out.u_right = setup.camera.bf() > 0 ? pixel.x() - setup.camera.bf() / p_cam.z() : -1;
  out.level = point->predict_level(distance, setup.pyramid);
  out.view_cos = view_cos;
  return out;
}

namespace {

// Drops matches whose keypoint-angle change disagrees with the dominant ones.
int filter_by_orientation(Frame& current, const std::vector<std::size_t>& matched,
                          const std::vector<float>& angle_differences) {
  const std::vector<bool> keep = rotation_consistent(angle_differences);
  int removed = 0;
  for (std::size_t k = 0; k < matched.size(); ++k) {
    if (!keep[k]) {
      current.set_map_point(matched[k], nullptr);
      ++removed;
    }
  }
  return removed;
}

bool slot_taken(const Frame& frame, std::size_t j) {
  const MapPointPtr& mp = frame.map_point(j);
  return mp && mp->num_observations() > 0;
}

}  // namespace

int search_by_projection(Frame& current, const Frame& last, float radius_factor,
                         bool check_orientation) {
  const CameraSetup& setup = current.setup();
  const PinholeCamera& camera = setup.camera;
  const Eigen::Isometry3d& T_cw = current.T_cam_world();
  // Current camera centre seen from the last camera: forward/backward motion
  // along the optical axis shifts the expected pyramid levels.
  const Eigen::Vector3d t_lc = last.T_cam_world() * current.camera_center();
  const bool forward = t_lc.z() > camera.baseline();
  const bool backward = -t_lc.z() > camera.baseline();

  std::vector<std::size_t> matched;
  std::vector<float> angle_differences;
  for (std::size_t i = 0; i < last.size(); ++i) {
    const MapPointPtr& mp = last.map_point(i);
    if (!mp || last.is_outlier(i) || mp->is_bad()) continue;
    const Eigen::Vector3d p_cam = T_cw * mp->position();
    if (p_cam.z() <= 0) continue;
    const Eigen::Vector2d uv = camera.project(p_cam);
    if (!camera.in_image(uv)) continue;
    const int last_level = last.keypoint(i).octave;
    const float radius = radius_factor * setup.pyramid.scale[static_cast<std::size_t>(last_level)];
    std::vector<std::size_t> candidates;
    if (forward) {
      candidates = current.features_in_area(uv.x(), uv.y(), radius, last_level, -1);
    } else if (backward) {
      candidates = current.features_in_area(uv.x(), uv.y(), radius, 0, last_level);
    } else {
      candidates = current.features_in_area(uv.x(), uv.y(), radius, std::max(last_level - 1, 0),
                                            last_level + 1);
    }
    const double u_right = camera.bf() > 0 ? uv.x() - camera.bf() / p_cam.z() : -1;
    int best_distance = 256;
    std::ptrdiff_t best = -1;
    for (std::size_t j : candidates) {
      if (slot_taken(current, j)) continue;
      if (current.u_right(j) >= 0 && std::abs(u_right - current.u_right(j)) > radius) continue;
      const int d = descriptor_distance(mp->descriptor(), current.descriptor(j));
      if (d < best_distance) {
        best_distance = d;
        best = static_cast<std::ptrdiff_t>(j);
      }
    }
    if (best >= 0 && best_distance <= kDescriptorDistanceHigh) {
      const auto b = static_cast<std::size_t>(best);
      current.set_map_point(b, mp);
      matched.push_back(b);
      angle_differences.push_back(current.keypoint(b).angle - last.keypoint(i).angle);
    }
  }
  int n = static_cast<int>(matched.size());
  if (check_orientation) n -= filter_by_orientation(current, matched, angle_differences);
  return n;
}

int search_by_projection(Frame& current, const std::vector<ProjectedPoint>& points, float th,
                         float ratio) {
  const CameraSetup& setup = current.setup();
  int n = 0;
  for (const ProjectedPoint& p : points) {
    if (p.point->is_bad()) continue;
    const float window = p.view_cos > 0.998 ? 2.5f : 4.0f;
    const float radius = th * window * setup.pyramid.scale[static_cast<std::size_t>(p.level)];
    const auto candidates = current.features_in_area(static_cast<float>(p.pixel.x()),
                                                     static_cast<float>(p.pixel.y()), radius,
                                                     std::max(p.level - 1, 0), p.level);
    int best_distance = 256, second_distance = 256;
    int best_level = -1, second_level = -1;
    std::ptrdiff_t best = -1;
    for (std::size_t j : candidates) {
      if (slot_taken(current, j)) continue;
      if (current.u_right(j) >= 0 && p.u_right >= 0 && std::abs(p.u_right - current.u_right(j)) > radius) {
        continue;
      }
      const int d = descriptor_distance(p.point->descriptor(), current.descriptor(j));
      if (d < best_distance) {
        second_distance = best_distance;
        second_level = best_level;
        best_distance = d;
        best_level = current.keypoint(j).octave;
        best = static_cast<std::ptrdiff_t>(j);
      } else if (d < second_distance) {
        second_distance = d;
        second_level = current.keypoint(j).octave;
      }
    }
    if (best < 0 || best_distance > kDescriptorDistanceHigh) continue;
    if (best_level == second_level && best_distance > ratio * second_distance) continue;
    current.set_map_point(static_cast<std::size_t>(best), p.point);
    ++n;
  }
  return n;
}

}  // namespace stillslam
