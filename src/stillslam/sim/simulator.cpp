#include "stillslam/sim/simulator.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "stillslam/core/error.h"
#include "stillslam/sim/assets.h"
#include "stillslam/sim/scene_layout.h"

namespace stillslam::sim {
namespace {

// The room is fixed (about 5 x 6 m); a replayed path that wanders farther
// would look through the walls. Say so rather than render nonsense silently.
void warn_if_outside_room(const CameraMotion& motion, const Eigen::Isometry3d& T_world_scene, double seconds) {
  const Eigen::Isometry3d T_scene_world = T_world_scene.inverse();
  double worst = 0;
  for (int i = 0; i <= 200; ++i) {
    const Eigen::Vector3d p = T_scene_world * motion.pose_at(seconds * i / 200.0).translation();
    worst = std::max({worst, SceneLayout::kMinX + 0.3 - p.x(), p.x() - SceneLayout::kMaxX + 0.3,
                      SceneLayout::kMinY + 0.3 - p.y(), p.y() - SceneLayout::kMaxY + 0.3,
                      SceneLayout::kFloorZ + 0.3 - p.z(), p.z() - SceneLayout::kCeilingZ + 0.2});
  }
  if (worst > 0) {
    spdlog::warn("sim: the camera path leaves the simulated room by up to {:.2f} m; images will show "
                 "the outside of the walls (use a shorter --frames or a smaller trajectory)",
                 worst);
  }
}

// The cut-out to hold in front of the lens and the texture point to centre:
// the one whose window around that point (the part of a person seen from
// DynamicObjects::kOccluderDistance, with a margin) is the most opaque.
void pick_occluder(const std::vector<cv::Mat>& cutouts, const std::vector<int>& texture_ids,
                   const CameraCalibration& camera, PeopleTextures& out) {
  constexpr double kHeight = 1.75;
  const double half_w = 1.2 * DynamicObjects::kOccluderDistance * (camera.width / 2.0) / camera.fx;
  const double half_h = 1.2 * DynamicObjects::kOccluderDistance * (camera.height / 2.0) / camera.fy;
  double best = -1;
  for (std::size_t i = 0; i < cutouts.size(); ++i) {
    const cv::Mat& c = cutouts[i];
    if (c.channels() != 4 || c.empty()) continue;
    const double metres_per_px = kHeight / c.rows;  // square texels
    const int hw = std::max(1, static_cast<int>(half_w / metres_per_px));
    const int hh = std::max(1, static_cast<int>(half_h / metres_per_px));
    for (double v = 0.2; v <= 0.6 + 1e-9; v += 0.05) {
      for (double u = 0.3; u <= 0.7 + 1e-9; u += 0.05) {
        const int cx = static_cast<int>(u * c.cols), cy = static_cast<int>(v * c.rows);
        const cv::Rect window = cv::Rect(cx - hw, cy - hh, 2 * hw, 2 * hh);
        const cv::Rect inside = window & cv::Rect(0, 0, c.cols, c.rows);
        if (inside.area() == 0) continue;
        cv::Mat alpha;
        cv::extractChannel(c(inside), alpha, 3);
        const double opaque = cv::countNonZero(alpha > 127) / static_cast<double>(window.area());
        if (opaque > best + 1e-9) {
          best = opaque;
          out.occluder = texture_ids[i];
          out.occluder_size = c.size();
          out.occluder_centre = Eigen::Vector2d(u, v);
        }
      }
    }
  }
}

}  // namespace

CameraCalibration camera_from_options(const SimulationOptions& o) {
  if (o.width < 16 || o.height < 16) throw Error("--width/--height must be at least 16 pixels");
  CameraCalibration c;
  const double sx = o.width / 640.0, sy = o.height / 480.0;
  c.fx = o.fx * sx;
  c.fy = o.fy * sy;
  // Pixel-centre convention: scale the continuous image, then shift back.
  c.cx = (o.cx + 0.5) * sx - 0.5;
  c.cy = (o.cy + 0.5) * sy - 0.5;
  c.width = o.width;
  c.height = o.height;
  return c;
}

Simulator::Simulator(SimulationOptions options) : options_(std::move(options)) {
  if (options_.frames < 1) throw Error("--frames must be at least 1");
  if (options_.fps <= 0) throw Error("fps must be positive");
  if (options_.data_dir.empty()) options_.data_dir = find_data_dir();
  noise_ = noise_model(options_.noise);
  motion_ = CameraMotion::create(options_.trajectory, options_.data_dir, options_.seed);
  const double available = std::floor(motion_.duration() * options_.fps + 1e-9) + 1;
  frames_ = static_cast<int>(std::min<double>(options_.frames, available));
  const double seconds = (frames_ - 1) / options_.fps;
  T_world_scene_ = scene_frame_for(motion_, seconds);
  warn_if_outside_room(motion_, T_world_scene_, seconds);

  const AssetLibrary assets = load_assets(options_.data_dir);
  std::vector<MipTexture> textures;
  std::vector<cv::Size> texture_sizes;
  PeopleTextures people;
  for (const auto& t : assets.textures) {
    textures.emplace_back(t);
    texture_sizes.push_back(t.size());
  }
  for (const auto& c : assets.cutouts) {
    people.walking.push_back(static_cast<int>(textures.size()));
    textures.emplace_back(c);
    people.walking_sizes.push_back(c.size());
  }
  for (const auto& c : assets.sitting) {
    people.sitting.push_back(static_cast<int>(textures.size()));
    textures.emplace_back(c);
    people.sitting_sizes.push_back(c.size());
  }
  const CameraCalibration camera = camera_from_options(options_);
  pick_occluder(assets.cutouts, people.walking, camera, people);
  renderer_ = std::make_unique<Renderer>(camera, std::move(textures));
  if (options_.moved_chair && options_.still_people >= 2 && !options_.no_people) {
    throw Error("sim: --moved-chair pushes the chair the second still person sits on; use --still-people 1 or 0");
  }
  std::vector<Quad> chair;
  static_quads_ = build_static_scene(T_world_scene_, texture_sizes, options_.seed,
                                     options_.moved_chair ? &chair : nullptr);
  DynamicObjectsOptions dyn;
  dyn.walking = options_.no_people ? 0 : std::max(0, options_.people);
  dyn.still = options_.no_people ? 0 : std::max(0, options_.still_people);
  dyn.moved_box = options_.moved_object;
  dyn.duration = seconds;
  dyn.half_view_tan = (camera.width / 2.0) / camera.fx;
  if (!options_.no_people && options_.occlude_at) {
    if (options_.occlude_seconds <= 0) throw Error("--occlude T:D needs a positive duration D");
    dyn.occlude_at = options_.occlude_at;
    dyn.occlude_seconds = options_.occlude_seconds;
  }
  if (!options_.no_people && options_.crowd_at) {
    if (options_.crowd_seconds <= 0) throw Error("--crowd T:D needs a positive duration D");
    dyn.crowd_at = options_.crowd_at;
    dyn.crowd_seconds = options_.crowd_seconds;
  }
  // The camera path every 0.1 s: people walk across its lines of sight.
  std::vector<TimedPose> camera_path;
  const int samples = std::max(1, static_cast<int>(std::ceil(seconds / 0.1)));
  for (int i = 0; i <= samples; ++i) {
    const double t = seconds * i / samples;
    camera_path.push_back({t, motion_.pose_at(t)});
  }
  dynamic_ = std::make_unique<DynamicObjects>(dyn, T_world_scene_, camera_path, people, texture_sizes,
                                              options_.seed, std::move(chair));
}

Eigen::Isometry3d Simulator::T_left_right() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation().x() = options_.baseline;
  return T;
}

std::int64_t Simulator::stamp_ns(int index) const {
  return motion_.start_ns() + std::llround(index * 1e6 / options_.fps) * 1000LL;
}

Eigen::Isometry3d Simulator::pose(int index) const {
  return motion_.pose_at((stamp_ns(index) - motion_.start_ns()) * 1e-9);
}

std::vector<Quad> Simulator::quads_at(double t, const Eigen::Isometry3d& T_world_cam) const {
  std::vector<Quad> quads = static_quads_;
  // The static reference run keeps the movable box where it rests at t = 0.
  const double t_dyn = options_.no_people ? 0.0 : t;
  for (Quad& q : dynamic_->quads_at(t_dyn, T_world_cam)) quads.push_back(q);
  return quads;
}

SimFrame Simulator::render_frame(int index) const {
  if (index < 0 || index >= frames_) {
    throw Error("sim: frame " + std::to_string(index) + " out of range [0, " + std::to_string(frames_) + ")");
  }
  SimFrame f;
  f.index = index;
  f.stamp_ns = stamp_ns(index);
  f.timestamp = static_cast<double>(f.stamp_ns) * 1e-9;
  const double t = (f.stamp_ns - motion_.start_ns()) * 1e-9;
  f.T_world_cam = motion_.pose_at(t);
  const std::vector<Quad> quads = quads_at(t, f.T_world_cam);

  auto exposure = [&](const Eigen::Isometry3d& offset) {
    std::vector<Eigen::Isometry3d> poses;
    const int n = noise_.exposure_samples;
    for (int k = 0; k < n && n > 1; ++k) {
      const double dt = (static_cast<double>(k) / (n - 1) - 0.5) * noise_.exposure_fraction / options_.fps;
      poses.push_back(motion_.pose_at(t + dt) * offset);
    }
    return poses;
  };
  const RenderedView view = renderer_->render_blurred(quads, f.T_world_cam,
                                                      exposure(Eigen::Isometry3d::Identity()),
                                                      options_.supersampling);
  // One RNG stream per frame: frames can be rendered in any order, same bytes.
  cv::RNG rng(options_.seed * 1000003ULL + static_cast<std::uint64_t>(index) * 7919ULL + 1);
  f.bgr = apply_image_noise(view.bgr, noise_, rng);
  f.depth = apply_depth_noise(view.depth, noise_, rng);
  f.dynamic_ids = view.dynamic_ids;
  f.mask = view.mask();
  if (options_.stereo) {
    const Eigen::Isometry3d T_right = f.T_world_cam * T_left_right();
    const RenderedView right = renderer_->render_blurred(quads, T_right, exposure(T_left_right()),
                                                         options_.supersampling);
    f.right_bgr = apply_image_noise(right.bgr, noise_, rng);
    cv::cvtColor(f.right_bgr, f.right_gray, cv::COLOR_BGR2GRAY);
  }
  return f;
}

}  // namespace stillslam::sim
