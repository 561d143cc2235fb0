#include "stillslam/sim/walking_paths.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stillslam/sim/scene_layout.h"

namespace stillslam::sim {
namespace {

using V2 = Eigen::Vector2d;

constexpr double kStep = 0.05;  // metres between the points checked along a path

double segment_distance(const V2& a, const V2& b, const V2& p) {
  const V2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}

}  // namespace

WalkingPathPlanner::WalkingPathPlanner(std::vector<CameraSample> samples, WalkingPathOptions options)
    : samples_(std::move(samples)), options_(options) {
  for (const Eigen::AlignedBox3d& box : SceneLayout::furniture()) {
    const V2 r = V2::Constant(options_.body_radius);
    obstacles_.emplace_back(V2(box.min().head<2>()) - r, V2(box.max().head<2>()) + r);
    if (box.max().z() >= options_.hiding_top_z) tall_.emplace_back(box.min().head<2>(), box.max().head<2>());
  }
}

bool WalkingPathPlanner::free(const V2& p) const {
  const double w = options_.wall_clearance;
  if (p.x() < SceneLayout::kMinX + w || p.x() > SceneLayout::kMaxX - w || p.y() < SceneLayout::kMinY + w ||
      p.y() > SceneLayout::kMaxY - w) {
    return false;
  }
  return std::none_of(obstacles_.begin(), obstacles_.end(),
                      [&](const Eigen::AlignedBox2d& b) { return b.contains(p); });
}

double WalkingPathPlanner::free_run(const V2& p, const V2& dir, double cap) const {
  double s = 0;
  while (s + kStep <= cap && free(p + (s + kStep) * dir)) s += kStep;
  return s;
}

bool WalkingPathPlanner::hidden(const V2& from, const V2& to) const {
  const double len = (to - from).norm();
  for (double s = 0; s <= len; s += kStep) {
    const V2 q = from + (to - from) * (s / std::max(len, 1e-9));
    for (const Eigen::AlignedBox2d& b : tall_) {
      if (b.contains(q)) return true;
    }
  }
  return false;
}

double WalkingPathPlanner::camera_distance(const V2& a, const V2& b) const {
  double best = std::numeric_limits<double>::infinity();
  for (const CameraSample& s : samples_) best = std::min(best, segment_distance(a, b, s.position.head<2>()));
  return best;
}

std::optional<WalkingPath> WalkingPathPlanner::plan(double t, double preferred_distance) const {
  // The line of sight around t: mean position and mean optical axis over +-1 s
  // (a hand-held path shakes; a person crosses the view for a second or more).
  V2 c = V2::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();
  int n = 0;
  for (const CameraSample& s : samples_) {
    if (std::abs(s.t - t) > 1.0) continue;
    c += s.position.head<2>();
    axis += s.optical_axis;
    ++n;
  }
  if (n == 0) return std::nullopt;
  c /= n;
  V2 forward = axis.head<2>() / n;
  if (forward.norm() < 0.2) return std::nullopt;  // looking (almost) straight up or down
  forward.normalize();
  const V2 across(forward.y(), -forward.x());  // image right

  std::optional<WalkingPath> best;
  double best_score = -std::numeric_limits<double>::infinity();
  for (double d = options_.min_distance; d <= options_.max_distance + 1e-9; d += 0.02) {
    const V2 p = c + d * forward;
    if (!free(p) || hidden(c, p)) continue;
    // To leave the view a person walks half its width at d plus half a body beyond.
    const double reach = d * options_.half_view_tan + 0.5;
    for (const double deviation : {0.0, 0.35, -0.35}) {
      const V2 dir = Eigen::Rotation2Dd(deviation) * across;
      const double s1 = free_run(p, -dir, reach + 0.3), s2 = free_run(p, dir, reach + 0.3);
      if (std::min(s1, s2) < 0.4) continue;
      const V2 a = p - s1 * dir, b = p + s2 * dir;
      if (camera_distance(a, b) < options_.camera_clearance) continue;
      // Prefer the wanted distance, then paths that leave the view, then straight across.
      const double shortfall = std::max(0.0, reach - s1) + std::max(0.0, reach - s2);
      const double score = -std::abs(d - preferred_distance) - shortfall - 0.3 * std::abs(deviation);
      if (score > best_score) {
        best_score = score;
        best = WalkingPath{a, b, s1 / (s1 + s2), d, t};
      }
    }
  }
  return best;
}

std::optional<WalkingPath> WalkingPathPlanner::plan_near(double t, double preferred_distance) const {
  if (samples_.empty()) return std::nullopt;
  const double t0 = samples_.front().t, t1 = samples_.back().t;
  for (int k = 0; k <= 2 * static_cast<int>(std::ceil((t1 - t0) / 0.5)) + 1; ++k) {
    const double ti = t + (k % 2 == 0 ? 1 : -1) * 0.5 * ((k + 1) / 2);
    if (ti < t0 - 1e-9 || ti > t1 + 1e-9) continue;
    if (auto path = plan(ti, preferred_distance)) return path;
  }
  return std::nullopt;
}

}  // namespace stillslam::sim
