#include "stillslam/sim/dynamic_objects.h"

#include <algorithm>
#include <cmath>

namespace stillslam::sim {
namespace {

constexpr double kTwoPi = 6.283185307179586;
using V = Eigen::Vector3d;

// Smooth 0 -> 1 over [0, 1].
double smooth(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * (3 - 2 * s);
}

}  // namespace

DynamicObjects::DynamicObjects(const DynamicObjectsOptions& options,
                               const Eigen::Isometry3d& T_world_scene,
                               const std::vector<int>& cutout_textures,
                               const std::vector<cv::Size>& cutout_sizes,
                               const std::vector<int>& sitting_textures,
                               const std::vector<cv::Size>& sitting_sizes,
                               const std::vector<cv::Size>& texture_sizes, std::uint64_t seed)
    : options_(options), T_world_scene_(T_world_scene) {
  PanelPainter rng(texture_sizes, seed * 31 + 7);
  std::uint16_t next_id = 1;
  const int n_cut = static_cast<int>(cutout_textures.size());
  const int first = n_cut > 0 ? static_cast<int>(rng.uniform(0, n_cut)) : 0;
  auto make = [&](int i) {
    PersonTrack p;
    const int c = (first + i) % std::max(1, n_cut);
    p.texture = cutout_textures[c];
    p.aspect = static_cast<double>(cutout_sizes[c].width) / cutout_sizes[c].height;
    p.height = rng.uniform(1.62, 1.85);
    p.id = next_id++;
    return p;
  };
  for (int i = 0; i < options.walking && n_cut > 0; ++i) {
    PersonTrack p = make(i);
    // Alternate: close in front of the desk (covers up to half the image), then behind it.
    const bool near = i % 2 == 0;
    // Far paths run between the chairs and the front wall.
    const double y = near ? rng.uniform(0.8, 1.25) : rng.uniform(3.05, 3.15);
    const double slant = near ? rng.uniform(-0.25, 0.25) : rng.uniform(-0.08, 0.08);
    const double xa = near ? -1.6 : -2.3, xb = near ? 2.3 : 1.15;
    const bool flip = rng.uniform(0, 1) < 0.5;
    p.a = Eigen::Vector2d(flip ? xb : xa, y - slant);
    p.b = Eigen::Vector2d(flip ? xa : xb, y + slant);
    p.speed = rng.uniform(0.8, 1.3);
    p.pause = rng.uniform(0.5, 3.0);
    // Every other person stops in view for a while (talking, looking around).
    p.stop_at = rng.uniform(0.35, 0.65);
    p.stop_time = i % 2 == 1 || i >= 2 ? rng.uniform(1.5, 4.0) : 0.0;
    p.offset = rng.uniform(0, 8.0) + 3.0 * i;
    people_.push_back(p);
  }
  for (int i = 0; i < options.still && n_cut > 0; ++i) {
    PersonTrack p = make(options.walking + i);
    if (!sitting_textures.empty()) {
      const int c = i % static_cast<int>(sitting_textures.size());
      p.texture = sitting_textures[c];
      p.aspect = static_cast<double>(sitting_sizes[c].width) / sitting_sizes[c].height;
      p.height = rng.uniform(1.2, 1.3);  // seated, feet on the floor
    }
    p.still = true;
    const Eigen::Vector3d chair = SceneLayout::chair_front(i % 2);
    p.a = p.b = Eigen::Vector2d(chair.x(), chair.y() - 0.5 * (i / 2));
    people_.push_back(p);
  }
  if (options.moved_box) {
    box_id_ = next_id++;
    const V lo(0.3, 1.6, SceneLayout::kDeskTopZ);
    rng.box(lo, lo + V(0.28, 0.22, 0.2), box_);
  }
}

V DynamicObjects::person_foot(const PersonTrack& p, double t) const {
  if (p.still) return V(p.a.x(), p.a.y(), SceneLayout::kFloorZ);
  const double len = (p.b - p.a).norm();
  // One leg: walk to the stop point, stand there, walk on.
  const double walk = len / p.speed + p.stop_time;
  auto along = [&](double tau) {  // fraction of the path done after tau seconds of a leg
    const double t_stop = p.stop_at * len / p.speed;
    if (tau < t_stop) return tau * p.speed / len;
    if (tau < t_stop + p.stop_time) return p.stop_at;
    return std::min(1.0, (tau - p.stop_time) * p.speed / len);
  };
  const double period = 2 * (walk + p.pause);
  const double tau = std::fmod(t + p.offset, period);
  Eigen::Vector2d xy;
  if (tau < walk) {
    xy = p.a + (p.b - p.a) * along(tau);
  } else if (tau < walk + p.pause) {
    xy = p.b;
  } else if (tau < 2 * walk + p.pause) {
    xy = p.b + (p.a - p.b) * along(tau - walk - p.pause);
  } else {
    xy = p.a;
  }
  return V(xy.x(), xy.y(), SceneLayout::kFloorZ);
}

std::vector<Quad> DynamicObjects::quads_at(double t, const V& camera_world) const {
  std::vector<Quad> out;
  const V cam = T_world_scene_.inverse() * camera_world;
  for (const PersonTrack& p : people_) {
    V foot = person_foot(p, t);
    // Steps at ~1.8 Hz: the body rises twice per stride and sways sideways once.
    const double step = p.still ? 0.3 : 1.8;
    const double bob = (p.still ? 0.005 : 0.025) * std::abs(std::sin(kTwoPi * step * 0.5 * t + p.offset));
    V to_cam = cam - foot;
    to_cam.z() = 0;
    if (to_cam.norm() < 1e-6) to_cam = V(0, -1, 0);
    to_cam.normalize();
    const V right = V::UnitZ().cross(to_cam);  // image right as the camera sees the billboard
    foot += right * ((p.still ? 0.01 : 0.02) * std::sin(kTwoPi * step * 0.25 * t + p.offset));
    const double w = p.height * p.aspect;
    Quad q;
    q.origin = foot - right * (w / 2) + V(0, 0, p.height + bob);
    q.axis_u = right * w;
    q.axis_v = V(0, 0, -p.height);
    q.texture = p.texture;
    q.alpha_tested = true;
    q.dynamic_id = p.id;
    out.push_back(q);
  }
  if (!box_.empty()) {
    // Picked up at 40% of the sequence, carried 0.8 m left and 0.4 m back over 2.5 s.
    const double t0 = 0.4 * options_.duration, dur = 2.5;
    const double s = smooth((t - t0) / dur);
    const bool moving = t > t0 && t < t0 + dur;
    const V shift = V(-0.8 * s, 0.35 * s, 0.25 * std::sin(M_PI * s));
    for (Quad q : box_) {
      q.origin += shift;
      q.dynamic_id = moving ? box_id_ : 0;
      out.push_back(q);
    }
  }
  for (Quad& q : out) {
    q.origin = T_world_scene_ * q.origin;
    q.axis_u = T_world_scene_.linear() * q.axis_u;
    q.axis_v = T_world_scene_.linear() * q.axis_v;
  }
  return out;
}

}  // namespace stillslam::sim
