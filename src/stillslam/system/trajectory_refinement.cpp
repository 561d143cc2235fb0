#include "stillslam/system/trajectory_refinement.h"

namespace stillslam {

namespace {

// The point that now stands for mp (fusion replaces points, possibly in a
// chain); nullptr when it was culled.
const MapPoint* current_point(const MapPointPtr& mp) {
  const MapPoint* p = mp.get();
  while (p != nullptr && p->is_bad()) p = p->replaced_by().get();
  return p;
}

}  // namespace

FrameObservations collect_frame_observations(const Frame& frame) {
  FrameObservations out;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const MapPointPtr& mp = frame.map_point(i);
    if (!mp || frame.is_outlier(i) || mp->num_observations() < 1) continue;
    const cv::KeyPoint& kp = frame.keypoint(i);
    out.points.push_back(mp);
    out.observations.push_back({kp.pt.x, kp.pt.y, frame.u_right(i), static_cast<std::uint8_t>(kp.octave)});
  }
  return out;
}

std::optional<Eigen::Isometry3d> refine_frame_pose(const CameraSetup& setup, const Eigen::Isometry3d& T_cam_world,
                                                   const FrameObservations& frame,
                                                   const TrajectoryRefinementOptions& options) {
  std::vector<PoseObservation> observations, kept;
  observations.reserve(frame.observations.size());
  for (std::size_t k = 0; k < frame.observations.size(); ++k) {
    const MapPoint* mp = current_point(frame.points[k]);
    if (mp == nullptr) continue;
    const FrameObservations::Observation& o = frame.observations[k];
    PoseObservation obs;
    obs.point_world = mp->position();
    obs.pixel = Eigen::Vector2d(o.x, o.y);
    obs.u_right = o.u_right;
    obs.inv_sigma2 = setup.pyramid.inv_sigma2[o.level];
    if (mp->on_dynamic_instance()) obs.inv_sigma2 /= options.kept_point_sigma * options.kept_point_sigma;
    (options.leave_out_kept_points && mp->on_dynamic_instance() ? kept : observations).push_back(obs);
  }
  // Too few without the kept person's points: all of them.
  if (static_cast<int>(observations.size()) < std::max(3, options.min_inliers)) {
    observations.insert(observations.end(), kept.begin(), kept.end());
  }
  if (static_cast<int>(observations.size()) < std::max(3, options.min_inliers)) return std::nullopt;
  const PoseOptimizationResult result = optimize_pose(setup.camera, T_cam_world, observations, options.pose);
  if (result.num_inliers < options.min_inliers) return std::nullopt;
  return result.T_cam_world;
}

}  // namespace stillslam
