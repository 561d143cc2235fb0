#pragma once
// Motion-only bundle adjustment: refine one camera pose against fixed map
// points, classifying each observation as inlier/outlier (ORB-SLAM style).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "stillslam/geometry/pinhole_camera.h"
#include "stillslam/optimize/observation_options.h"
#include "stillslam/optimize/pose_prior.h"

namespace stillslam {

struct PoseObservation {
  Eigen::Vector3d point_world = Eigen::Vector3d::Zero();
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // undistorted
  double u_right = -1;    // >= 0: stereo/RGB-D observation (3-dof residual, needs camera.bf() > 0)
  double inv_sigma2 = 1;  // 1/sigma^2 of the keypoint's pyramid level
};

struct PoseOptimizerOptions {
  // Each round optimizes on the current inliers, then re-classifies every
  // observation (outliers are re-tested and may come back).
  int rounds = 4;
  int iterations_per_round = 10;
  double chi2_mono = kChi2Mono95;
  double chi2_stereo = kChi2Stereo95;
  // Huber loss (delta = sqrt(chi2)) on all rounds but the last.
  bool huber = true;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

struct PoseOptimizationResult {
  Eigen::Isometry3d T_cam_world = Eigen::Isometry3d::Identity();
  std::vector<bool> inlier;  // per observation, after the last round
  int num_inliers = 0;
};

// Observations whose point is behind the camera count as outliers. With no
// observations the initial pose is returned unchanged. A prior (pose_prior.h)
// adds its residual to every round; outliers are classified as without it.
PoseOptimizationResult optimize_pose(const PinholeCamera& camera,
                                     const Eigen::Isometry3d& T_cam_world_init,
                                     const std::vector<PoseObservation>& observations,
                                     const PoseOptimizerOptions& options = {},
                                     const PosePrior* prior = nullptr);

}  // namespace stillslam
