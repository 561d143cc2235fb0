#include "stillslam/mapping/point_triangulation.h"

#include <cmath>
#include <mutex>

#include "stillslam/core/option_check.h"
#include "stillslam/geometry/triangulation.h"
#include "stillslam/optimize/observation_options.h"

namespace stillslam {

namespace {

// Whitened reprojection error of a world point in a keyframe observation.
bool consistent(const KeyFrame& kf, std::size_t i, const Eigen::Vector3d& p_world) {
  const CameraSetup& setup = kf.setup();
  const Eigen::Vector3d p = kf.T_cam_world() * p_world;
  if (p.z() <= 0) return false;
  const Eigen::Vector2d uv = setup.camera.project(p);
  const cv::KeyPoint& kp = kf.keypoint(i);
  const double sigma2 = setup.pyramid.sigma2[static_cast<std::size_t>(kp.octave)];
  const double ex = uv.x() - kp.pt.x, ey = uv.y() - kp.pt.y;
  if (kf.u_right(i) < 0) return ex * ex + ey * ey <= kChi2Mono95 * sigma2;
  const double er = uv.x() - setup.camera.bf() / p.z() - kf.u_right(i);
  return ex * ex + ey * ey + er * er <= kChi2Stereo95 * sigma2;
}

double stereo_cos_parallax(const KeyFrame& kf, std::size_t i) {
  if (kf.depth(i) <= 0 || kf.u_right(i) < 0) return 2.0;  // "no stereo": larger than any cosine
  return std::cos(2.0 * std::atan2(kf.setup().camera.baseline() / 2.0, kf.depth(i)));
}

}  // namespace

int create_new_points(Map& map, KeyFrame& kf, std::vector<MapPointPtr>& recent,
                      const PointTriangulationOptions& options, const std::function<bool()>& should_stop) {
  std::vector<KeyFrame*> neighbours;
  {
    std::lock_guard<std::mutex> lock(map.update_mutex());
    neighbours = kf.best_covisibles(options.neighbours);
  }
  const CameraSetup& setup = kf.setup();
  const PinholeCamera& camera = setup.camera;
  const ScalePyramid& pyramid = setup.pyramid;
  const float ratio_factor = 1.5f * pyramid.scale_factor;
  TriangulationOptions dlt;
  dlt.max_cos_parallax = 0.99999;
  int created = 0;
  for (std::size_t n = 0; n < neighbours.size(); ++n) {
    if (n > 0 && should_stop && should_stop()) break;
    std::lock_guard<std::mutex> lock(map.update_mutex());
    KeyFrame& kf2 = *neighbours[n];
    if (kf2.is_bad()) continue;
    const Eigen::Vector3d center1 = kf.camera_center(), center2 = kf2.camera_center();
    if ((center2 - center1).norm() < camera.baseline()) continue;
    const Eigen::Isometry3d T1 = kf.T_cam_world(), T2 = kf2.T_cam_world();
    for (const auto& [i1, i2] : search_for_triangulation(kf, kf2, options.search)) {
      if (kf.map_point(i1) || kf2.map_point(i2)) continue;
      const cv::KeyPoint& kp1 = kf.keypoint(i1);
      const cv::KeyPoint& kp2 = kf2.keypoint(i2);
      const Eigen::Vector3d xn1 = camera.normalized({kp1.pt.x, kp1.pt.y});
      const Eigen::Vector3d xn2 = camera.normalized({kp2.pt.x, kp2.pt.y});
      const Eigen::Vector3d ray1 = T1.linear().transpose() * xn1;
      const Eigen::Vector3d ray2 = T2.linear().transpose() * xn2;
      const double cos_rays = ray1.dot(ray2) / (ray1.norm() * ray2.norm());
      const double cos_stereo1 = stereo_cos_parallax(kf, i1);
      const double cos_stereo2 = stereo_cos_parallax(kf2, i2);
      const double cos_stereo = std::min(cos_stereo1, cos_stereo2);
      const bool stereo1 = cos_stereo1 <= 1.0, stereo2 = cos_stereo2 <= 1.0;
      std::optional<Eigen::Vector3d> x;
      if (cos_rays < cos_stereo && cos_rays > 0 && (stereo1 || stereo2 || cos_rays < 0.9998)) {
        x = triangulate(xn1, T1, xn2, T2, dlt);
      } else if (stereo1 && cos_stereo1 < cos_stereo2) {
        x = kf.unproject(i1);
      } else if (stereo2 && cos_stereo2 < cos_stereo1) {
        x = kf2.unproject(i2);
      }
      if (!x) continue;
      if (!consistent(kf, i1, *x) || !consistent(kf2, i2, *x)) continue;
      const double dist1 = (*x - center1).norm(), dist2 = (*x - center2).norm();
      if (dist1 <= 0 || dist2 <= 0) continue;
      const double ratio_dist = dist2 / dist1;
      const double ratio_octave = pyramid.scale[static_cast<std::size_t>(kp1.octave)] /
                                  pyramid.scale[static_cast<std::size_t>(kp2.octave)];
      if (ratio_dist * ratio_factor < ratio_octave || ratio_dist > ratio_octave * ratio_factor) continue;

      MapPointPtr mp = map.create_map_point(*x, &kf);
      mp->add_observation(&kf, i1);
      mp->add_observation(&kf2, i2);
      kf.set_map_point(i1, mp);
      kf2.set_map_point(i2, mp);
      mp->compute_distinctive_descriptor();
      mp->update_normal_and_depth(pyramid);
      recent.push_back(std::move(mp));
      ++created;
    }
  }
  return created;
}

void PointTriangulationOptions::check() const {
  option_check::at_least("PointTriangulationOptions.neighbours", static_cast<double>(neighbours), 1);
}

}  // namespace stillslam
