#include "stillslam/sim/dynamic_objects.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "stillslam/sim/random.h"

namespace stillslam::sim {
namespace {

using V = Eigen::Vector3d;

// Smooth 0 -> 1 over [0, 1].
double smooth(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * (3 - 2 * s);
}

// A slow shift away from the stop point and back (PersonTrack::dawdle): a
// random direction, 0.15-0.3 m, shortened until the whole shift stays on free
// floor and clear of the camera path at both stop points (one per leg).
Eigen::Vector2d dawdle_offset(const WalkingPathPlanner& planner, const WalkingPath& path, double stop_at,
                              PanelPainter& rng) {
  const Eigen::Vector2d stops[] = {path.a + stop_at * (path.b - path.a), path.b + stop_at * (path.a - path.b)};
  const double angle = rng.uniform(0, kTwoPi);
  Eigen::Vector2d offset = rng.uniform(0.15, 0.3) * Eigen::Vector2d(std::cos(angle), std::sin(angle));
  for (; offset.norm() > 0.02; offset *= 0.5) {
    bool ok = true;
    for (const Eigen::Vector2d& stop : stops) {
      ok = ok && planner.camera_distance(stop, stop + offset) >= 0.6;
      for (double s = 0; ok && s <= 1.0; s += 0.25) ok = planner.free(stop + s * offset);
    }
    if (ok) return offset;
  }
  return Eigen::Vector2d::Zero();
}

// A person's cut-out standing at `foot` (scene frame), turned to face `cam`
// (for a still person: the camera's start),
// with the bob and sway of walking (or the slight sway of a still person).
Quad billboard(int texture, double height, double aspect, V foot, const V& cam, double t, double phase, bool still,
               std::uint16_t id) {
  // Steps at ~1.8 Hz: the body rises twice per stride and sways sideways once.
  const double step = still ? 0.3 : 1.8;
  const double bob = (still ? 0.005 : 0.025) * std::abs(std::sin(kTwoPi * step * 0.5 * t + phase));
  V to_cam = cam - foot;
  to_cam.z() = 0;
  if (to_cam.norm() < 1e-6) to_cam = V(0, -1, 0);
  to_cam.normalize();
  const V right = V::UnitZ().cross(to_cam);  // image right as the camera sees the billboard
  foot += right * ((still ? 0.01 : 0.02) * std::sin(kTwoPi * step * 0.25 * t + phase));
  const double w = height * aspect;
  Quad q;
  q.origin = foot - right * (w / 2) + V(0, 0, height + bob);
  q.axis_u = right * w;
  q.axis_v = V(0, 0, -height);
  q.texture = texture;
  q.alpha_tested = true;
  q.dynamic_id = id;
  return q;
}

// The chair is pushed 0.6 m to the right (away from the desk, towards the
// cabinet) over 2 s from 65% of the sequence.
constexpr double kChairStart = 0.65, kChairSeconds = 2.0;

}  // namespace

DynamicObjects::DynamicObjects(const DynamicObjectsOptions& options, const Eigen::Isometry3d& T_world_scene,
                               const std::vector<TimedPose>& camera_path, const PeopleTextures& textures,
                               const std::vector<cv::Size>& texture_sizes, std::uint64_t seed,
                               std::vector<Quad> chair)
    : options_(options), T_world_scene_(T_world_scene), textures_(textures), chair_(std::move(chair)) {
  PanelPainter rng(texture_sizes, seed * 31 + 7);
  std::uint16_t next_id = 1;
  const int n_cut = static_cast<int>(textures.walking.size());
  const int first = n_cut > 0 ? static_cast<int>(rng.uniform(0, n_cut)) : 0;
  auto make = [&](int i) {
    PersonTrack p;
    const int c = (first + i) % std::max(1, n_cut);
    p.texture = textures.walking[c];
    p.aspect = static_cast<double>(textures.walking_sizes[c].width) / textures.walking_sizes[c].height;
    p.height = rng.uniform(1.62, 1.85);
    p.id = next_id++;
    return p;
  };
  std::vector<CameraSample> samples;
  const Eigen::Isometry3d T_scene_world = T_world_scene.inverse();
  for (const TimedPose& tp : camera_path) {
    const Eigen::Isometry3d T_scene_cam = T_scene_world * tp.T_world_cam;
    samples.push_back({tp.t, T_scene_cam.translation(), T_scene_cam.linear().col(2)});
  }
  WalkingPathOptions path_options;
  path_options.half_view_tan = options.half_view_tan;
  const WalkingPathPlanner planner(std::move(samples), path_options);
  for (int i = 0; i < options.walking && n_cut > 0; ++i) {
    PersonTrack p = make(i);
    // Alternate: close (1-1.4 m: covers up to about half the image), then farther away. Each
    // person crosses the line of sight the camera has at its own anchor time,
    // spread over the sequence.
    const bool near = i % 2 == 0;
    const double preferred = near ? rng.uniform(1.0, 1.4) : rng.uniform(1.6, 2.6);
    const double slot = options.duration / options.walking;
    const double anchor = slot * (i + 0.5) + rng.uniform(-0.15, 0.15) * slot;
    std::optional<WalkingPath> path = planner.plan_near(anchor, preferred);
    if (!path) {
      // The camera never looks across free floor (e.g. it faces a wall closely):
      // walk across the room in front of the scene origin instead.
      spdlog::warn("sim: no free floor across the camera's line of sight for person {}; walking across the room", i);
      const double y = near ? 1.0 : 3.1;
      path = WalkingPath{{-1.6, y}, {2.3, y}, 0.4, y, anchor};
    }
    if (rng.uniform(0, 1) < 0.5) {
      std::swap(path->a, path->b);
      path->crossing = 1 - path->crossing;
    }
    p.a = path->a;
    p.b = path->b;
    p.speed = rng.uniform(0.6, 1.3);
    p.pause = rng.uniform(0.5, 3.0);
    // Every other person stops in view for a while (talking, looking around).
    p.stop_at = std::clamp(path->crossing + rng.uniform(-0.1, 0.1), 0.1, 0.9);
    p.stop_time = i % 2 == 1 || i >= 2 ? rng.uniform(3.0, 6.0) : 0.0;
    if (p.stop_time > 0) p.dawdle = dawdle_offset(planner, *path, p.stop_at, rng);
    // Phase the back-and-forth so the person passes the crossing at the anchor time.
    const double len = (p.b - p.a).norm();
    const double period = 2 * (len / p.speed + p.stop_time + p.pause);
    const double reach_crossing = path->crossing * len / p.speed + (path->crossing > p.stop_at ? p.stop_time : 0.0);
    p.offset = std::fmod(reach_crossing - anchor + rng.uniform(-0.5, 0.5) + 100 * period, period);
    people_.push_back(p);
    paths_.push_back(*path);
  }
  for (int i = 0; i < options.still && n_cut > 0; ++i) {
    PersonTrack p = make(options.walking + i);
    if (!textures.sitting.empty()) {
      const int c = i % static_cast<int>(textures.sitting.size());
      p.texture = textures.sitting[c];
      p.aspect = static_cast<double>(textures.sitting_sizes[c].width) / textures.sitting_sizes[c].height;
      p.height = rng.uniform(1.2, 1.3);  // seated, feet on the floor
    }
    p.still = true;
    const Eigen::Vector3d chair = SceneLayout::chair_front(i % 2);
    p.a = p.b = Eigen::Vector2d(chair.x(), chair.y() - 0.5 * (i / 2));
    // Turning towards a camera that circles them would move their texture
    // several centimetres: not still.
    if (!camera_path.empty()) p.faces = (T_scene_world * camera_path.front().T_world_cam.translation()).head<2>();
    people_.push_back(p);
  }
  if (options.moved_box) {
    box_id_ = next_id++;
    const V lo(0.3, 1.6, SceneLayout::kDeskTopZ);
    rng.box(lo, lo + V(0.28, 0.22, 0.2), box_);
  }
  if (!chair_.empty()) chair_id_ = next_id++;
  if (options.occlude_at && textures.occluder >= 0) occluder_id_ = next_id++;
  if (options.crowd_at && n_cut > 0) place_crowd(camera_path, next_id, rng);
}

void DynamicObjects::place_crowd(const std::vector<TimedPose>& camera_path, std::uint16_t& next_id,
                                 PanelPainter& rng) {
  // Where the camera is and looks (horizontally) in the middle of the crowd's time.
  const double t_mid = *options_.crowd_at + 0.5 * options_.crowd_seconds;
  const TimedPose* mid = &camera_path.front();
  for (const TimedPose& tp : camera_path) {
    if (std::abs(tp.t - t_mid) < std::abs(mid->t - t_mid)) mid = &tp;
  }
  const Eigen::Isometry3d T_scene_cam = T_world_scene_.inverse() * mid->T_world_cam;
  const Eigen::Vector2d cam = T_scene_cam.translation().head<2>();
  Eigen::Vector2d forward = T_scene_cam.linear().col(2).head<2>();
  if (forward.norm() < 1e-6) forward = Eigen::Vector2d(0, 1);
  forward.normalize();
  const Eigen::Vector2d right(forward.y(), -forward.x());  // image right seen from above (z up)
  // Two rows (0.9 and 1.3 m away) walking right to left at 1 m/s, 0.35 m
  // apart along the walk: the lead reaches the left edge of the far row's
  // view at crowd_at, the last leaves its right edge at crowd_at + crowd_seconds.
  constexpr double kSpeed = 1.0, kSpacing = 0.35, kMargin = 0.6, kNear = 0.9, kFar = 1.3;
  const double half_far = kFar * options_.half_view_tan;
  const int count = static_cast<int>(std::ceil((2 * half_far + kSpeed * options_.crowd_seconds) / kSpacing)) + 1;
  const int n_cut = static_cast<int>(textures_.walking.size());
  for (int j = 0; j < count; ++j) {
    CrowdMember m;
    const int c = j % n_cut;
    m.texture = textures_.walking[c];
    m.aspect = static_cast<double>(textures_.walking_sizes[c].width) / textures_.walking_sizes[c].height;
    m.height = rng.uniform(1.6, 1.85);
    const double depth = j % 2 == 0 ? kNear : kFar;
    const double half = depth * options_.half_view_tan + kMargin;
    const Eigen::Vector2d centre = cam + depth * forward + rng.uniform(-0.1, 0.1) * forward;
    m.a = centre + half * right;
    m.b = centre - half * right;
    m.speed = kSpeed * rng.uniform(0.95, 1.05);
    // x_j(t) = -half_far - v (t - crowd_at) + j * spacing, and x_j(t_start) = +half.
    m.t_start = *options_.crowd_at + (j * kSpacing - half_far - half) / kSpeed;
    m.id = next_id++;
    crowd_.push_back(m);
  }
}

std::optional<Eigen::Vector3d> DynamicObjects::crowd_foot(const CrowdMember& m, double t) const {
  const double len = (m.b - m.a).norm();
  const double s = (t - m.t_start) * m.speed / len;
  if (s < 0 || s > 1) return std::nullopt;
  const Eigen::Vector2d xy = m.a + s * (m.b - m.a);
  return V(xy.x(), xy.y(), SceneLayout::kFloorZ);
}

std::pair<double, double> DynamicObjects::chair_motion() const {
  if (chair_.empty()) return {0.0, 0.0};
  const double t0 = kChairStart * options_.duration;
  return {t0, t0 + kChairSeconds};
}

std::vector<InstanceInfo> DynamicObjects::instances() const {
  std::vector<InstanceInfo> out;
  for (const PersonTrack& p : people_) {
    out.push_back({p.id, p.still ? "still_person" : "walking_person", "person", !p.still});
  }
  if (box_id_ != 0) out.push_back({box_id_, "moved_box", "box", true});
  if (chair_id_ != 0) out.push_back({chair_id_, "moved_chair", "chair", true});
  if (occluder_id_ != 0) out.push_back({occluder_id_, "occluder", "person", true});
  for (const CrowdMember& m : crowd_) out.push_back({m.id, "crowd_person", "person", true});
  std::sort(out.begin(), out.end(), [](const InstanceInfo& a, const InstanceInfo& b) { return a.id < b.id; });
  return out;
}

V DynamicObjects::person_foot(const PersonTrack& p, double t) const {
  if (p.still) return V(p.a.x(), p.a.y(), SceneLayout::kFloorZ);
  const double len = (p.b - p.a).norm();
  // One leg: walk to the stop point, stand there, walk on.
  const double walk = len / p.speed + p.stop_time;
  const double t_stop = p.stop_at * len / p.speed;
  auto along = [&](double tau) {  // fraction of the path done after tau seconds of a leg
    if (tau < t_stop) return tau * p.speed / len;
    if (tau < t_stop + p.stop_time) return p.stop_at;
    return std::min(1.0, (tau - p.stop_time) * p.speed / len);
  };
  auto shift = [&](double tau) -> Eigen::Vector2d {  // the dawdle while stopped
    if (tau < t_stop || tau >= t_stop + p.stop_time) return Eigen::Vector2d::Zero();
    return p.dawdle * std::sin(std::numbers::pi * (tau - t_stop) / p.stop_time);
  };
  const double period = 2 * (walk + p.pause);
  const double tau = std::fmod(t + p.offset, period);
  Eigen::Vector2d xy;
  if (tau < walk) {
    xy = p.a + (p.b - p.a) * along(tau) + shift(tau);
  } else if (tau < walk + p.pause) {
    xy = p.b;
  } else if (tau < 2 * walk + p.pause) {
    xy = p.b + (p.a - p.b) * along(tau - walk - p.pause) + shift(tau - walk - p.pause);
  } else {
    xy = p.a;
  }
  return V(xy.x(), xy.y(), SceneLayout::kFloorZ);
}

std::vector<Quad> DynamicObjects::quads_at(double t, const Eigen::Isometry3d& T_world_cam) const {
  std::vector<Quad> out;
  const V cam = T_world_scene_.inverse() * T_world_cam.translation();
  for (const PersonTrack& p : people_) {
    const V toward = p.still ? V(p.faces.x(), p.faces.y(), cam.z()) : cam;
    out.push_back(billboard(p.texture, p.height, p.aspect, person_foot(p, t), toward, t, p.offset, p.still, p.id));
  }
  for (const CrowdMember& m : crowd_) {
    if (const std::optional<V> foot = crowd_foot(m, t)) {
      out.push_back(billboard(m.texture, m.height, m.aspect, *foot, cam, t, m.t_start, false, m.id));
    }
  }
  if (!box_.empty()) {
    // Picked up at 40% of the sequence, carried 0.8 m left and 0.4 m back over 2.5 s.
    const double t0 = 0.4 * options_.duration, dur = 2.5;
    const double s = smooth((t - t0) / dur);
    const bool moving = t > t0 && t < t0 + dur;
    const V shift = V(-0.8 * s, 0.35 * s, 0.25 * std::sin(std::numbers::pi * s));
    for (Quad q : box_) {
      q.origin += shift;
      q.dynamic_id = moving ? box_id_ : 0;
      out.push_back(q);
    }
  }
  if (!chair_.empty()) {
    const auto [t0, t1] = chair_motion();
    const double s = smooth((t - t0) / (t1 - t0));
    const bool moving = t > t0 && t < t1;
    // Pushed, not lifted: it slides 0.6 m and drifts 5 cm back and forth.
    const V shift = V(0.6 * s, 0.05 * std::sin(std::numbers::pi * s), 0);
    for (Quad q : chair_) {
      q.origin += shift;
      q.dynamic_id = moving ? chair_id_ : 0;
      out.push_back(q);
    }
  }
  for (Quad& q : out) {
    q.origin = T_world_scene_ * q.origin;
    q.axis_u = T_world_scene_.linear() * q.axis_u;
    q.axis_v = T_world_scene_.linear() * q.axis_v;
  }
  if (const std::optional<Quad> q = occluder_at(t, T_world_cam)) out.push_back(*q);
  return out;
}

std::optional<Quad> DynamicObjects::occluder_at(double t, const Eigen::Isometry3d& T_world_cam) const {
  if (occluder_id_ == 0) return std::nullopt;
  const double start = *options_.occlude_at, end = start + options_.occlude_seconds;
  if (t <= start - kOccluderWalk || t >= end + kOccluderWalk) return std::nullopt;
  // A person 1.75 m tall seen from kOccluderDistance: it stays in front of the
  // lens (moves with the camera) so the view is covered whatever the camera does.
  const double height = 1.75;
  const double width = height * textures_.occluder_size.width / std::max(1, textures_.occluder_size.height);
  const Eigen::Vector2d& c = textures_.occluder_centre;
  // Walks in from the right and out to the left: sideways offset of the torso.
  const double out_of_view = kOccluderDistance * options_.half_view_tan + width;
  double x = 0;
  if (t < start) x = out_of_view * (1 - smooth((t - (start - kOccluderWalk)) / kOccluderWalk));
  if (t > end) x = -out_of_view * smooth((t - end) / kOccluderWalk);
  const Eigen::Matrix3d& R = T_world_cam.linear();
  const V centre = T_world_cam * V(x, 0, kOccluderDistance);
  Quad q;
  q.axis_u = R.col(0) * width;   // image right
  q.axis_v = R.col(1) * height;  // image down
  q.origin = centre - q.axis_u * c.x() - q.axis_v * c.y();
  q.texture = textures_.occluder;
  q.alpha_tested = true;
  q.dynamic_id = occluder_id_;
  return q;
}

}  // namespace stillslam::sim
