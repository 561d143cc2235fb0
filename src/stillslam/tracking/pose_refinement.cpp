#include "stillslam/tracking/pose_refinement.h"

namespace stillslam {

PoseObservation pose_observation(const Frame& frame, std::size_t i) {
  PoseObservation obs;
  obs.point_world = frame.map_point(i)->position();
  const cv::KeyPoint& kp = frame.keypoint(i);
  obs.pixel = Eigen::Vector2d(kp.pt.x, kp.pt.y);
  obs.u_right = frame.u_right(i);
  obs.inv_sigma2 = frame.setup().pyramid.inv_sigma2[static_cast<std::size_t>(kp.octave)];
  return obs;
}

std::vector<PoseObservation> inlier_observations(const Frame& frame) {
  std::vector<PoseObservation> observations;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (frame.map_point(i) && !frame.is_outlier(i)) observations.push_back(pose_observation(frame, i));
  }
  return observations;
}

int refine_pose(Frame& frame, const PoseOptimizerOptions& options, const PosePrior* prior) {
  const CameraSetup& setup = frame.setup();
  std::vector<PoseObservation> observations;
  std::vector<std::size_t> index;
  observations.reserve(frame.size());
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const MapPointPtr& mp = frame.map_point(i);
    if (!mp) continue;
    frame.set_outlier(i, false);
    observations.push_back(pose_observation(frame, i));
    index.push_back(i);
  }
  if (observations.size() < 3) return 0;
  const PoseOptimizationResult result = optimize_pose(setup.camera, frame.T_cam_world(), observations, options, prior);
  frame.set_pose(result.T_cam_world);
  for (std::size_t k = 0; k < index.size(); ++k) frame.set_outlier(index[k], !result.inlier[k]);
  return result.num_inliers;
}

int discard_outliers(Frame& frame) {
  int map_inliers = 0;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const MapPointPtr& mp = frame.map_point(i);
    if (!mp) continue;
    if (frame.is_outlier(i)) {
      frame.set_map_point(i, nullptr);
      frame.set_outlier(i, false);
    } else if (mp->num_observations() > 0) {
      ++map_inliers;
    }
  }
  return map_inliers;
}

}  // namespace stillslam
