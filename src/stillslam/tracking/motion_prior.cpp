#include "stillslam/tracking/motion_prior.h"

#include "stillslam/core/option_check.h"

namespace stillslam {

std::optional<PosePrior> motion_prior(const Eigen::Isometry3d& predicted, const MotionPriorOptions& options) {
  if (!options.enabled()) return std::nullopt;
  PosePrior prior;
  prior.T_cam_world = predicted;
  prior.sigma_translation = options.sigma_translation;
  prior.sigma_rotation = options.sigma_rotation;
  prior.dead_zone = options.dead_zone;
  return prior;
}

int refine_pose_with_prior(Frame& frame, const PoseOptimizerOptions& pose, const StaticEvidenceOptions& evidence,
                           const std::optional<PosePrior>& prior, const MotionPriorOptions& options, bool* applied) {
  if (applied != nullptr) *applied = false;
  if (!prior) return refine_pose_on_evidence(frame, pose, evidence);
  if (options.gate > 0) {
    const Eigen::Isometry3d start = frame.T_cam_world();
    const int inliers = refine_pose_on_evidence(frame, pose, evidence);
    const double offset = (camera_centre(frame.T_cam_world()) - camera_centre(prior->T_cam_world)).norm();
    if (offset <= options.gate) return inliers;
    frame.set_pose(start);
  }
  if (applied != nullptr) *applied = true;
  return refine_pose_on_evidence(frame, pose, evidence, &*prior);
}

void MotionPriorOptions::check() const {
  using namespace option_check;
  at_least("MotionPriorOptions.sigma_translation", sigma_translation, 0);
  above("MotionPriorOptions.sigma_rotation", sigma_rotation, 0);
  at_least("MotionPriorOptions.dead_zone", dead_zone, 0);
  at_least("MotionPriorOptions.gate", gate, 0);
}

}  // namespace stillslam
