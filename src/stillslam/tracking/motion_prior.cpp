#include "stillslam/tracking/motion_prior.h"

#include <algorithm>
#include <vector>

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
                           const std::optional<PosePrior>& prior, const MotionPriorOptions& options, MotionPriorStep* step,
                           const StartEvidence* start_evidence) {
  MotionPriorStep local;
  if (step == nullptr) step = &local;
  *step = MotionPriorStep{};
  if (!prior) return refine_pose_on_evidence(frame, pose, evidence, nullptr, start_evidence);
  if (options.gate <= 0) {
    step->applied = true;
    return refine_pose_on_evidence(frame, pose, evidence, &*prior, start_evidence);
  }
  const Eigen::Isometry3d start = frame.T_cam_world();
  const int free_inliers = refine_pose_on_evidence(frame, pose, evidence, nullptr, start_evidence);
  step->offset = (camera_centre(frame.T_cam_world()) - camera_centre(prior->T_cam_world)).norm();
  if (step->offset <= options.gate) return free_inliers;
  const Eigen::Isometry3d free_pose = frame.T_cam_world();
  std::vector<bool> free_outlier(frame.size());
  for (std::size_t i = 0; i < frame.size(); ++i) free_outlier[i] = frame.is_outlier(i);
  frame.set_pose(start);
  const int inliers = refine_pose_on_evidence(frame, pose, evidence, &*prior, start_evidence);
  int rejected = 0;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    rejected += frame.map_point(i) && !free_outlier[i] && frame.is_outlier(i);
  }
  step->rejected_share = free_inliers > 0 ? static_cast<double>(rejected) / free_inliers : 0;
  bool keep = true;
  if (options.refit) {
    Frame kept = frame;
    for (std::size_t i = 0; i < kept.size(); ++i) {
      if (kept.is_outlier(i)) kept.set_map_point(i, nullptr);
    }
    refine_pose_on_evidence(kept, pose, evidence, nullptr, start_evidence);
    step->refit_offset = (camera_centre(kept.T_cam_world()) - camera_centre(prior->T_cam_world)).norm();
    keep = step->refit_offset <= options.gate;
  }
  if (keep) {
    step->applied = true;
    return inliers;
  }
  // The points as a whole leave the prediction: the pose without the prior.
  frame.set_pose(free_pose);
  for (std::size_t i = 0; i < frame.size(); ++i) frame.set_outlier(i, free_outlier[i]);
  return free_inliers;
}

void MotionPriorFrame::add(const MotionPriorStep& step) {
  applied += step.applied ? 1 : 0;
  offset = std::max(offset, step.offset);
  rejected_share = std::max(rejected_share, step.rejected_share);
  refit_offset = std::max(refit_offset, step.refit_offset);
}

void MotionPriorOptions::check() const {
  using namespace option_check;
  at_least("MotionPriorOptions.sigma_translation", sigma_translation, 0);
  above("MotionPriorOptions.sigma_rotation", sigma_rotation, 0);
  at_least("MotionPriorOptions.dead_zone", dead_zone, 0);
  at_least("MotionPriorOptions.gate", gate, 0);
}

}  // namespace stillslam
