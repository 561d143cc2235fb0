#include "stillslam/sim/scene_layout.h"

#include <algorithm>
#include <cmath>

#include "stillslam/core/error.h"

namespace stillslam::sim {
namespace {

using V = Eigen::Vector3d;

// Tiles the rectangle origin + [0,1]u + [0,1]v with panels of about `size` metres.
void tile(PanelPainter& p, const V& origin, const V& u, const V& v, double size_u, double size_v,
          std::vector<Quad>& out, float bmin = 0.85f, float bmax = 1.05f) {
  const int nu = std::max(1, static_cast<int>(std::round(u.norm() / size_u)));
  const int nv = std::max(1, static_cast<int>(std::round(v.norm() / size_v)));
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      out.push_back(p.panel(origin + u * (double(i) / nu) + v * (double(j) / nv), u / nu, v / nv,
                            bmin, bmax));
    }
  }
}

}  // namespace

PanelPainter::PanelPainter(const std::vector<cv::Size>& texture_sizes, std::uint64_t seed)
    : sizes_(texture_sizes), rng_(seed) {
  if (sizes_.empty()) throw Error("sim scene: no textures to paint with");
}

double PanelPainter::uniform(double a, double b) { return rng_.uniform(a, b); }

Quad PanelPainter::panel(const V& origin, const V& axis_u, const V& axis_v, float bmin, float bmax) {
  Quad q;
  q.origin = origin;
  q.axis_u = axis_u;
  q.axis_v = axis_v;
  q.texture = std::min(static_cast<int>(uniform(0, sizes_.size())), static_cast<int>(sizes_.size()) - 1);
  const cv::Size s = sizes_[q.texture];
  const double aspect = axis_u.norm() / axis_v.norm();  // panel width / height
  const double scale = uniform(0.5, 1.0);
  double w = scale * s.width, h = w / aspect;  // crop in pixels
  if (h > scale * s.height) {
    h = scale * s.height;
    w = h * aspect;
  }
  const double x0 = uniform(0, s.width - w), y0 = uniform(0, s.height - h);
  q.u0 = static_cast<float>(x0 / s.width);
  q.v0 = static_cast<float>(y0 / s.height);
  q.u1 = static_cast<float>((x0 + w) / s.width);
  q.v1 = static_cast<float>((y0 + h) / s.height);
  q.brightness = static_cast<float>(uniform(bmin, bmax));
  return q;
}

void PanelPainter::box(const V& lo, const V& hi, std::vector<Quad>& out) {
  const V d = hi - lo;
  const V ex(d.x(), 0, 0), ey(0, d.y(), 0), ez(0, 0, d.z());
  const V top(lo.x(), lo.y(), hi.z());
  out.push_back(panel(top + ey, ex, -ey));                  // top (far edge = texture top)
  out.push_back(panel(top, ex, -ez));                       // front (y = lo)
  out.push_back(panel(top + ey + ex, -ex, -ez));            // back (y = hi)
  out.push_back(panel(top + ey, -ey, -ez));                 // left (x = lo)
  out.push_back(panel(top + ex, ey, -ez));                  // right (x = hi)
}

Eigen::Isometry3d scene_frame_for(const CameraMotion& motion, double seconds) {
  if (!motion.replayed()) return Eigen::Isometry3d::Identity();
  const double span = std::min(seconds, motion.duration());
  V mean_pos = V::Zero(), mean_down = V::Zero(), mean_fwd = V::Zero();
  const int n = 100;
  for (int i = 0; i < n; ++i) {
    const Eigen::Isometry3d T = motion.pose_at(span * i / (n - 1));
    mean_pos += T.translation() / n;
    mean_down += T.linear().col(1);
    mean_fwd += T.linear().col(2);
  }
  const V up = -mean_down.normalized();
  V fwd = mean_fwd - mean_fwd.dot(up) * up;
  if (fwd.norm() < 1e-6) throw Error("sim: cannot find a horizontal viewing direction in the trajectory");
  fwd.normalize();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = fwd.cross(up);
  T.linear().col(1) = fwd;
  T.linear().col(2) = up;
  T.translation() = mean_pos;
  return T;
}

std::vector<Quad> build_static_scene(const Eigen::Isometry3d& T_world_scene,
                                     const std::vector<cv::Size>& texture_sizes, std::uint64_t seed,
                                     std::vector<Quad>* movable_chair) {
  using L = SceneLayout;
  PanelPainter p(texture_sizes, seed);
  std::vector<Quad> q;
  const double h = L::kCeilingZ - L::kFloorZ;
  const V ez(0, 0, -h);  // walls: texture rows go down
  // Walls (texture x along the wall as seen from inside the room).
  tile(p, V(L::kMinX, L::kMaxY, L::kCeilingZ), V(L::kMaxX - L::kMinX, 0, 0), ez, 1.3, 0.9, q);  // front
  tile(p, V(L::kMaxX, L::kMinY, L::kCeilingZ), V(L::kMinX - L::kMaxX, 0, 0), ez, 1.3, 0.9, q);  // back
  tile(p, V(L::kMinX, L::kMinY, L::kCeilingZ), V(0, L::kMaxY - L::kMinY, 0), ez, 1.3, 0.9, q);  // left
  tile(p, V(L::kMaxX, L::kMaxY, L::kCeilingZ), V(0, L::kMinY - L::kMaxY, 0), ez, 1.3, 0.9, q);  // right
  // Floor (rugs) and ceiling (a bit darker).
  tile(p, V(L::kMinX, L::kMaxY, L::kFloorZ), V(L::kMaxX - L::kMinX, 0, 0),
       V(0, L::kMinY - L::kMaxY, 0), 1.2, 1.0, q, 0.75f, 0.95f);
  tile(p, V(L::kMinX, L::kMinY, L::kCeilingZ), V(L::kMaxX - L::kMinX, 0, 0),
       V(0, L::kMaxY - L::kMinY, 0), 1.5, 1.5, q, 0.65f, 0.8f);
  // Posters hang 2 cm off the walls: small depth steps and extra corners.
  for (int i = 0; i < 3; ++i) {
    const double w = p.uniform(0.5, 0.9), hh = p.uniform(0.5, 0.8);
    const double x = p.uniform(L::kMinX + 0.2, L::kMaxX - 0.2 - w);
    q.push_back(p.panel(V(x, L::kMaxY - 0.02, p.uniform(0.0, 0.9)), V(w, 0, 0), V(0, 0, -hh)));
    const double y = p.uniform(L::kMinY + 0.2, L::kMaxY - 0.3 - w);
    q.push_back(p.panel(V(L::kMinX + 0.02, y, p.uniform(0.0, 0.9)), V(0, w, 0), V(0, 0, -hh)));
    q.push_back(p.panel(V(L::kMaxX - 0.02, y + w, p.uniform(0.0, 0.9)), V(0, -w, 0), V(0, 0, -hh)));
  }
  // Furniture.
  const double f = L::kFloorZ;
  for (const Eigen::AlignedBox3d& b : {L::desk(), L::side_table(), L::cabinet(), L::shelf()}) {
    p.box(b.min(), b.max(), q);  // desk in front of the camera, side table left, cabinet front right, shelf behind
  }
  p.box(V(-0.35, 2.05, L::kDeskTopZ), V(0.35, 2.12, -0.22), q);  // monitor
  // Two chairs behind the desk: seat and backrest.
  for (int i = 0; i < 2; ++i) {
    const V c = L::chair_front(i);
    const std::size_t first = q.size();
    p.box(V(c.x() - 0.23, c.y() + 0.02, f), V(c.x() + 0.23, c.y() + 0.46, f + 0.46), q);
    p.box(V(c.x() - 0.23, c.y() + 0.42, f + 0.46), V(c.x() + 0.23, c.y() + 0.47, f + 0.95), q);
    if (i == 1 && movable_chair != nullptr) {
      movable_chair->assign(q.begin() + static_cast<std::ptrdiff_t>(first), q.end());
      q.resize(first);
    }
  }
  // Clutter on the desk and the side table.
  for (int i = 0; i < 3; ++i) {
    const double sx = p.uniform(0.12, 0.3), sy = p.uniform(0.12, 0.3), sz = p.uniform(0.08, 0.3);
    const double x = -0.75 + i * 0.5 + p.uniform(0, 0.45 - sx);
    const double y = p.uniform(1.55, 2.0 - sy);
    p.box(V(x, y, L::kDeskTopZ), V(x + sx, y + sy, L::kDeskTopZ + sz), q);
  }
  for (int i = 0; i < 2; ++i) {
    const double s = p.uniform(0.15, 0.35);
    const double y = 0.6 + i * 0.9 + p.uniform(0, 0.4);
    p.box(V(-2.3, y, -0.7), V(-2.3 + s, y + s, -0.7 + p.uniform(0.1, 0.35)), q);
  }
  for (Quad& quad : q) {
    quad.origin = T_world_scene * quad.origin;
    quad.axis_u = T_world_scene.linear() * quad.axis_u;
    quad.axis_v = T_world_scene.linear() * quad.axis_v;
  }
  return q;
}

}  // namespace stillslam::sim
