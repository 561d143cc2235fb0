#include "stillslam/tracking/depth_point_check.h"

#include "stillslam/core/option_check.h"
#include "stillslam/features/descriptor.h"
#include "stillslam/optimize/observation_options.h"
#include "stillslam/optimize/reprojection_costs.h"

namespace stillslam {

bool seen_where_predicted(const Frame& previous, const Eigen::Vector3d& point_world, const std::uint8_t* descriptor,
                          const DepthPointCheckOptions& options) {
  const CameraSetup& setup = previous.setup();
  const Eigen::Vector3d p = previous.T_cam_world() * point_world;
  if (p.z() < kMinCameraDepth) return false;
  const Eigen::Vector2d uv = setup.camera.project(p);
  const Intrinsics k(setup.camera);
  const float r = options.radius * setup.pyramid.scale.back();
  for (std::size_t j : previous.features_in_area(static_cast<float>(uv.x()), static_cast<float>(uv.y()), r)) {
    const cv::KeyPoint& kp = previous.keypoint(j);
    const auto level = static_cast<std::size_t>(kp.octave);
    const float dx = kp.pt.x - static_cast<float>(uv.x()), dy = kp.pt.y - static_cast<float>(uv.y());
    const float window = options.radius * setup.pyramid.scale[level];
    if (dx * dx + dy * dy > window * window) continue;
    if (descriptor_distance(descriptor, previous.descriptor(j)) > options.max_descriptor_distance) continue;
    const bool stereo = previous.u_right(j) >= 0 && k.bf > 0;
    const ReprojectionCheck c = check_reprojection(k, previous.T_cam_world(), point_world,
                                                   Eigen::Vector2d(kp.pt.x, kp.pt.y),
                                                   stereo ? previous.u_right(j) : -1.0, setup.pyramid.inv_sigma2[level]);
    if (c.in_front() && c.chi2 <= (stereo ? kChi2Stereo95 : kChi2Mono95)) return true;
  }
  return false;
}

void DepthPointCheckOptions::check() const {
  using namespace option_check;
  above("DepthPointCheckOptions.radius", radius, 0);
  in_range("DepthPointCheckOptions.max_descriptor_distance", max_descriptor_distance, 0, 256);
}

}  // namespace stillslam
