#include "stillslam/sim/renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stillslam/core/error.h"

namespace stillslam::sim {
namespace {

constexpr float kNear = 0.02f;  // metres; closer surfaces are ignored

// A quad expressed in one camera's frame, with what the inner loop needs.
struct CamQuad {
  Eigen::Vector3f origin, normal, du, dv;  // du = axis_u / |axis_u|^2 (projects to s)
  float plane_d = 0;                       // normal . origin
  float xmin = 0, xmax = 0, ymin = 0, ymax = 0;  // conservative pixel bounds
  float mip_scale = 0;                     // depth * mip_scale = texel footprint ratio
  const Quad* quad = nullptr;
};

struct Hit {
  float t = std::numeric_limits<float>::max();
  const CamQuad* q = nullptr;
  float s = 0, w = 0;
};

std::vector<CamQuad> to_camera(const std::vector<Quad>& quads, const Eigen::Isometry3d& T_world_cam,
                               const CameraCalibration& cam, const std::vector<MipTexture>& textures,
                               int supersampling) {
  const Eigen::Isometry3d T_cam_world = T_world_cam.inverse();
  std::vector<CamQuad> out;
  out.reserve(quads.size());
  for (const Quad& q : quads) {
    if (q.texture < 0 || q.texture >= static_cast<int>(textures.size())) {
      throw Error("sim renderer: quad refers to texture " + std::to_string(q.texture) +
                  " but only " + std::to_string(textures.size()) + " are loaded");
    }
    const Eigen::Vector3d o = T_cam_world * q.origin;
    const Eigen::Vector3d u = T_cam_world.linear() * q.axis_u;
    const Eigen::Vector3d v = T_cam_world.linear() * q.axis_v;
    const Eigen::Vector3d corners[4] = {o, o + u, o + v, o + u + v};
    CamQuad c;
    c.origin = o.cast<float>();
    c.normal = u.cross(v).normalized().cast<float>();
    c.du = (u / u.squaredNorm()).cast<float>();
    c.dv = (v / v.squaredNorm()).cast<float>();
    c.plane_d = c.normal.dot(c.origin);
    c.quad = &q;
    // One-sided: the visible side has axis_u to the right and axis_v down, i.e.
    // the normal u x v points away from the camera. Seen from behind = culled.
    if (c.plane_d <= 0) continue;
    bool all_front = true, any_front = false;
    for (const auto& p : corners) {
      all_front = all_front && p.z() > kNear;
      any_front = any_front || p.z() > kNear;
    }
    if (!any_front) continue;
    if (all_front) {
      c.xmin = c.ymin = std::numeric_limits<float>::max();
      c.xmax = c.ymax = std::numeric_limits<float>::lowest();
      for (const auto& p : corners) {
        const float x = static_cast<float>(cam.fx * p.x() / p.z() + cam.cx);
        const float y = static_cast<float>(cam.fy * p.y() / p.z() + cam.cy);
        c.xmin = std::min(c.xmin, x - 1);
        c.xmax = std::max(c.xmax, x + 1);
        c.ymin = std::min(c.ymin, y - 1);
        c.ymax = std::max(c.ymax, y + 1);
      }
      if (c.xmax < -1 || c.ymax < -1 || c.xmin > cam.width || c.ymin > cam.height) continue;
    } else {
      c.xmin = c.ymin = std::numeric_limits<float>::lowest();
      c.xmax = c.ymax = std::numeric_limits<float>::max();
    }
    // Pick the mip level whose texel matches the world footprint of one colour ray.
    const MipTexture& tex = textures[q.texture];
    const double texel = q.axis_u.norm() / (std::max(1e-6f, q.u1 - q.u0) * tex.width());
    c.mip_scale = static_cast<float>(1.0 / (cam.fx * std::max(1, supersampling) * texel));
    out.push_back(c);
  }
  return out;
}

inline void trace(const std::vector<const CamQuad*>& cands, const Eigen::Vector3f& ray, float px,
                  const std::vector<MipTexture>& textures, Hit& hit) {
  for (const CamQuad* c : cands) {
    if (px < c->xmin || px > c->xmax) continue;
    const float denom = c->normal.dot(ray);
    if (std::abs(denom) < 1e-9f) continue;
    const float t = c->plane_d / denom;
    if (t <= kNear || t >= hit.t) continue;
    const Eigen::Vector3f rel = t * ray - c->origin;
    const float s = rel.dot(c->du);
    const float w = rel.dot(c->dv);
    if (s < 0 || s > 1 || w < 0 || w > 1) continue;
    const Quad& q = *c->quad;
    if (q.alpha_tested &&
        !textures[q.texture].opaque(q.u0 + s * (q.u1 - q.u0), q.v0 + w * (q.v1 - q.v0))) {
      continue;
    }
    hit.t = t;
    hit.q = c;
    hit.s = s;
    hit.w = w;
  }
}

inline Rgba shade(const Hit& hit, const std::vector<MipTexture>& textures) {
  const Quad& q = *hit.q->quad;
  const float ratio = hit.t * hit.q->mip_scale;
  const int level = ratio >= 2.0f ? std::ilogb(ratio) : 0;
  Rgba c = textures[q.texture].sample(q.u0 + hit.s * (q.u1 - q.u0), q.v0 + hit.w * (q.v1 - q.v0),
                                      level);
  c.b *= q.brightness;
  c.g *= q.brightness;
  c.r *= q.brightness;
  return c;
}

void rows_candidates(const std::vector<CamQuad>& quads, float y, std::vector<const CamQuad*>& out) {
  out.clear();
  for (const CamQuad& c : quads) {
    if (y >= c.ymin && y <= c.ymax) out.push_back(&c);
  }
}

RenderedView render_impl(const CameraCalibration& cam, const std::vector<MipTexture>& textures,
                         const std::vector<Quad>& quads, const Eigen::Isometry3d& T_world_cam,
                         const std::vector<Eigen::Isometry3d>& exposure_poses, int supersampling) {
  if (cam.width <= 0 || cam.height <= 0 || cam.fx <= 0 || cam.fy <= 0) {
    throw Error("sim renderer: camera needs a positive image size and focal length");
  }
  const int ss = std::max(1, supersampling);
  const bool blur = exposure_poses.size() > 1;
  const std::vector<CamQuad> centre = to_camera(quads, T_world_cam, cam, textures, 1);
  const std::vector<CamQuad> centre_ss = to_camera(quads, T_world_cam, cam, textures, ss);
  std::vector<std::vector<CamQuad>> per_pose;
  if (blur) {
    for (const auto& T : exposure_poses) {
      per_pose.push_back(to_camera(quads, T, cam, textures, static_cast<int>(exposure_poses.size())));
    }
  }
  const float fx = static_cast<float>(cam.fx), fy = static_cast<float>(cam.fy);
  const float cx = static_cast<float>(cam.cx), cy = static_cast<float>(cam.cy);
  auto ray = [&](float pu, float pv) { return Eigen::Vector3f((pu - cx) / fx, (pv - cy) / fy, 1.0f); };

  RenderedView view;
  view.bgr.create(cam.height, cam.width, CV_32FC3);
  view.depth.create(cam.height, cam.width, CV_32FC1);
  view.dynamic_ids.create(cam.height, cam.width, CV_16UC1);
  // Index of the quad hit by each centre ray (-1 = none): finds the edges to supersample.
  cv::Mat hit_index(cam.height, cam.width, CV_32SC1);

  // Pass 1: one ray per pixel centre: exact depth, ids, and colour at the
  // one-ray mip level (or the motion-blurred average over the exposure).
  cv::parallel_for_(cv::Range(0, cam.height), [&](const cv::Range& range) {
    std::vector<const CamQuad*> cands;
    std::vector<std::vector<const CamQuad*>> pose_cands(per_pose.size());
    for (int v = range.start; v < range.end; ++v) {
      rows_candidates(centre, static_cast<float>(v), cands);
      auto* bgr = view.bgr.ptr<cv::Vec3f>(v);
      auto* depth = view.depth.ptr<float>(v);
      auto* ids = view.dynamic_ids.ptr<std::uint16_t>(v);
      auto* index = hit_index.ptr<int>(v);
      for (int u = 0; u < cam.width; ++u) {
        Hit hit;
        trace(cands, ray(static_cast<float>(u), static_cast<float>(v)), static_cast<float>(u), textures, hit);
        depth[u] = hit.q ? hit.t : 0.0f;
        ids[u] = hit.q ? hit.q->quad->dynamic_id : 0;
        index[u] = hit.q ? static_cast<int>(hit.q - centre.data()) : -1;
        if (!blur) {
          const Rgba c = hit.q ? shade(hit, textures) : Rgba{};
          bgr[u] = cv::Vec3f(c.b, c.g, c.r);
        }
      }
      if (!blur) continue;
      // Stratified: pose k gets sub-pixel offset k of an n x n pattern's diagonal.
      const int n = static_cast<int>(per_pose.size());
      for (int k = 0; k < n; ++k) {
        const float off = (k + 0.5f) / n - 0.5f;
        rows_candidates(per_pose[k], v + off, pose_cands[k]);
      }
      for (int u = 0; u < cam.width; ++u) {
        float b = 0, g = 0, r = 0;
        for (int k = 0; k < n; ++k) {
          const float off = (k + 0.5f) / n - 0.5f;
          const float pu = u + ((k * 7) % n + 0.5f) / n - 0.5f;
          Hit h;
          trace(pose_cands[k], ray(pu, v + off), pu, textures, h);
          if (!h.q) continue;
          const Rgba c = shade(h, textures);
          b += c.b;
          g += c.g;
          r += c.r;
        }
        bgr[u] = cv::Vec3f(b / n, g / n, r / n);
      }
    }
  });
  if (blur || ss == 1) return view;

  // Pass 2: anti-aliasing where the centre rays change surface (geometric and
  // alpha edges): ss x ss rays at the finer mip level.
  cv::parallel_for_(cv::Range(0, cam.height), [&](const cv::Range& range) {
    std::vector<std::vector<const CamQuad*>> sub_cands(ss);
    for (int v = range.start; v < range.end; ++v) {
      for (int j = 0; j < ss; ++j) {
        rows_candidates(centre_ss, v + (j + 0.5f) / ss - 0.5f, sub_cands[j]);
      }
      const int* above = hit_index.ptr<int>(std::max(0, v - 1));
      const int* here = hit_index.ptr<int>(v);
      const int* below = hit_index.ptr<int>(std::min(cam.height - 1, v + 1));
      auto* bgr = view.bgr.ptr<cv::Vec3f>(v);
      for (int u = 0; u < cam.width; ++u) {
        const int c = here[u];
        const bool edge = above[u] != c || below[u] != c || (u > 0 && here[u - 1] != c) ||
                          (u + 1 < cam.width && here[u + 1] != c);
        if (!edge) continue;
        float b = 0, g = 0, r = 0;
        for (int j = 0; j < ss; ++j) {
          for (int i = 0; i < ss; ++i) {
            const float pu = u + (i + 0.5f) / ss - 0.5f, pv = v + (j + 0.5f) / ss - 0.5f;
            Hit h;
            trace(sub_cands[j], ray(pu, pv), pu, textures, h);
            if (!h.q) continue;
            const Rgba col = shade(h, textures);
            b += col.b;
            g += col.g;
            r += col.r;
          }
        }
        const float inv = 1.0f / static_cast<float>(ss * ss);
        bgr[u] = cv::Vec3f(b * inv, g * inv, r * inv);
      }
    }
  });
  return view;
}

}  // namespace

cv::Mat RenderedView::mask() const {
  cv::Mat m;
  cv::compare(dynamic_ids, 0, m, cv::CMP_NE);
  return m;
}

Renderer::Renderer(const CameraCalibration& camera, std::vector<MipTexture> textures)
    : camera_(camera), textures_(std::move(textures)) {}

RenderedView Renderer::render(const std::vector<Quad>& quads, const Eigen::Isometry3d& T_world_cam,
                              int supersampling) const {
  return render_impl(camera_, textures_, quads, T_world_cam, {T_world_cam}, supersampling);
}

RenderedView Renderer::render_blurred(const std::vector<Quad>& quads,
                                      const Eigen::Isometry3d& T_world_cam,
                                      const std::vector<Eigen::Isometry3d>& exposure_poses,
                                      int supersampling) const {
  if (exposure_poses.empty()) return render(quads, T_world_cam, supersampling);
  return render_impl(camera_, textures_, quads, T_world_cam, exposure_poses, supersampling);
}

}  // namespace stillslam::sim
