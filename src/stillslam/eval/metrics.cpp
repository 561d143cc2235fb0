#include "stillslam/eval/metrics.h"

#include <cmath>

#include "stillslam/core/check.h"

namespace stillslam {

std::vector<double> absolute_translation_errors(const Trajectory& gt, const Trajectory& est) {
  STILLSLAM_CHECK_EQ(gt.size(), est.size(), "absolute_translation_errors: pass associated trajectories");
  std::vector<double> errors(gt.size());
  for (std::size_t k = 0; k < gt.size(); ++k) {
    errors[k] = (gt[k].T_world_cam.translation() - est[k].T_world_cam.translation()).norm();
  }
  return errors;
}

double rotation_angle_deg(const Eigen::Matrix3d& R) {
  // atan2 of |axis * sin| and cos keeps precision for tiny angles where acos does not.
  const Eigen::Vector3d axis_sin(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  const double cos_angle = 0.5 * (R.trace() - 1.0);
  return std::atan2(0.5 * axis_sin.norm(), cos_angle) * 180.0 / M_PI;
}

RelativeErrors relative_errors(const Trajectory& gt, const Trajectory& est, const std::vector<PosePair>& pairs) {
  STILLSLAM_CHECK_EQ(gt.size(), est.size(), "relative_errors: pass associated trajectories");
  RelativeErrors errors;
  errors.translation.reserve(pairs.size());
  errors.rotation_deg.reserve(pairs.size());
  for (const auto& [i, j] : pairs) {
    STILLSLAM_CHECK_LT(i, gt.size(), "relative_errors: a pose pair indexes past the trajectories");
    STILLSLAM_CHECK_LT(j, gt.size(), "relative_errors: a pose pair indexes past the trajectories");
    const Eigen::Isometry3d gt_rel = gt[i].T_world_cam.inverse() * gt[j].T_world_cam;
    const Eigen::Isometry3d est_rel = est[i].T_world_cam.inverse() * est[j].T_world_cam;
    const Eigen::Isometry3d E = gt_rel.inverse() * est_rel;
    errors.translation.push_back(E.translation().norm());
    errors.rotation_deg.push_back(rotation_angle_deg(E.linear()));
  }
  return errors;
}

}  // namespace stillslam
