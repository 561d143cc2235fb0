#include "stillslam/map/fuse.h"

#include "stillslam/features/descriptor.h"
#include "stillslam/map/matching_thresholds.h"
#include "stillslam/optimize/observation_options.h"

namespace stillslam {

int fuse(KeyFrame& keyframe, const std::vector<MapPointPtr>& points, float th) {
  const CameraSetup& setup = keyframe.setup();
  const PinholeCamera& camera = setup.camera;
  const Eigen::Isometry3d& T_cw = keyframe.T_cam_world();
  const Eigen::Vector3d center = keyframe.camera_center();
  int fused = 0;
  for (const MapPointPtr& mp : points) {
    if (!mp || mp->is_bad() || mp->is_provisional() || mp->is_observed_by(&keyframe)) continue;
    const Eigen::Vector3d p_cam = T_cw * mp->position();
    if (p_cam.z() <= 0) continue;
    const Eigen::Vector2d uv = camera.project(p_cam);
    if (!camera.in_image(uv)) continue;
    const double u_right = uv.x() - camera.bf() / p_cam.z();
    const Eigen::Vector3d ray = mp->position() - center;
    const double distance = ray.norm();
    if (distance < mp->min_distance() || distance > mp->max_distance()) continue;
    if (ray.dot(mp->normal()) < 0.5 * distance) continue;
    const int level = mp->predict_level(distance, setup.pyramid);
    const float radius = th * setup.pyramid.scale[static_cast<std::size_t>(level)];
    int best_distance = 256;
    std::ptrdiff_t best = -1;
    // Only keypoints at the predicted level or one below can match; the grid
    // filters by level, so most windows return nothing and allocate nothing.
    for (std::size_t j : keyframe.features_in_area(static_cast<float>(uv.x()), static_cast<float>(uv.y()), radius,
                                                   level - 1, level)) {
      const cv::KeyPoint& kp = keyframe.keypoint(j);
      const double ex = uv.x() - kp.pt.x, ey = uv.y() - kp.pt.y;
      const double inv_sigma2 = setup.pyramid.inv_sigma2[static_cast<std::size_t>(kp.octave)];
      if (keyframe.u_right(j) >= 0) {
        const double er = u_right - keyframe.u_right(j);
        if ((ex * ex + ey * ey + er * er) * inv_sigma2 > kChi2Stereo95) continue;
      } else if ((ex * ex + ey * ey) * inv_sigma2 > kChi2Mono95) {
        continue;
      }
      const int d = descriptor_distance(mp->descriptor(), keyframe.descriptor(j));
      if (d < best_distance) {
        best_distance = d;
        best = static_cast<std::ptrdiff_t>(j);
      }
    }
    if (best < 0 || best_distance > kDescriptorDistanceLow) continue;
    const auto j = static_cast<std::size_t>(best);
    const MapPointPtr existing = keyframe.map_point(j);
    if (existing && existing->is_provisional()) continue;  // its frame's own mask decides first
    if (existing && !existing->is_bad()) {
      if (existing->num_observations() > mp->num_observations()) {
        mp->replace_with(existing);
      } else {
        existing->replace_with(mp);
      }
    } else {
      mp->add_observation(&keyframe, j);
      keyframe.set_map_point(j, mp);
    }
    ++fused;
  }
  return fused;
}

}  // namespace stillslam
