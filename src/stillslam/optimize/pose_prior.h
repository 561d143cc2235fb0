#pragma once
// A Gaussian prior on one camera pose for optimize_pose (issue #20): the
// camera centre and orientation are pulled toward a predicted pose. Far
// static points fix the translation along the view only weakly; a close
// thing that earned static evidence and then moves can drag the pose there
// while the far points stay inside their chi2 bounds. The prior gives those
// weak directions a value to hold (the motion model's prediction).
#include <ceres/cost_function.h>
#include <Eigen/Geometry>

namespace stillslam {

struct PosePrior {
  Eigen::Isometry3d T_cam_world = Eigen::Isometry3d::Identity();  // the prior's mean
  double sigma_translation = 0.001;  // m, on the camera centre (per axis)
  double sigma_rotation = 0.01;      // rad, on the rotation vector of R * R_mean^T
  // Camera-centre offsets up to this many metres cost nothing; beyond, the
  // offset minus the dead zone is penalised (0: a plain Gaussian).
  double dead_zone = 0;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

// The prior as a Ceres cost over the 6-vector delta = [omega, v] of
// pose_residuals.h: T(delta) = [Exp(omega), v] * anchor. Six whitened
// residuals: the rotation vector of R(delta) * R_mean^T over sigma_rotation,
// then (camera centre - mean centre), shortened by the dead zone, over
// sigma_translation. The caller owns the returned cost (automatic
// derivatives: one 6x6 block per solve, cheap next to the reprojections).
ceres::CostFunction* make_pose_prior_cost(const Eigen::Isometry3d& anchor, const PosePrior& prior);

// Camera centre of a world-to-camera pose.
Eigen::Vector3d camera_centre(const Eigen::Isometry3d& T_cam_world);

}  // namespace stillslam
