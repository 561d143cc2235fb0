#include "stillslam/eval/evaluate.h"

#include <spdlog/spdlog.h>

#include <sstream>

#include "stillslam/core/error.h"

namespace stillslam {
namespace {

std::vector<double> stamps_of(const Trajectory& trajectory) {
  std::vector<double> stamps(trajectory.size());
  for (std::size_t i = 0; i < trajectory.size(); ++i) stamps[i] = trajectory[i].timestamp;
  return stamps;
}

Eigen::Matrix3Xd positions_of(const Trajectory& trajectory) {
  Eigen::Matrix3Xd positions(3, static_cast<Eigen::Index>(trajectory.size()));
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    positions.col(static_cast<Eigen::Index>(i)) = trajectory[i].T_world_cam.translation();
  }
  return positions;
}

}  // namespace

EvaluationResult evaluate(const Trajectory& gt, const Trajectory& est, const EvaluationOptions& options) {
  EvaluationResult result;
  result.gt_poses = gt.size();
  result.est_poses = est.size();
  const auto matches = associate(stamps_of(gt), stamps_of(est), options.association);
  if (matches.empty()) {
    std::ostringstream message;
    message << "no timestamps of the estimate (" << est.size() << " poses) match the ground truth (" << gt.size()
            << " poses) within " << options.association.effective_max_dt()
            << " s; check that both cover the same sequence and use the same time unit, or raise --max-dt";
    throw Error(message.str());
  }
  Trajectory est_associated;
  for (const IndexPair& m : matches) {
    result.gt.push_back(gt[m.gt]);
    est_associated.push_back(est[m.est]);
  }
  result.pairs = matches.size();

  result.alignment = align_positions(positions_of(est_associated), positions_of(result.gt), options.alignment);
  result.est_aligned = est_associated;
  for (StampedPose& pose : result.est_aligned) pose.T_world_cam = result.alignment.apply(pose.T_world_cam);

  result.ape = absolute_translation_errors(result.gt, result.est_aligned);
  result.ape_stats = compute_statistics(result.ape);

  result.rpe_pairs = select_pose_pairs(result.gt, options.rpe);
  result.rpe = relative_errors(result.gt, result.est_aligned, result.rpe_pairs);
  result.rpe_trans_stats = compute_statistics(result.rpe.translation);
  result.rpe_rot_stats = compute_statistics(result.rpe.rotation_deg);
  if (result.rpe_pairs.empty()) {
    spdlog::warn("RPE: no pose pair is {} {} apart among the {} associated poses; the RPE is absent (n/a, null in "
                 "JSON), lower --rpe-delta to get one",
                 options.rpe.delta, to_string(options.rpe.unit), result.pairs);
  }
  return result;
}

EvaluationResult evaluate_files(const std::filesystem::path& gt_path, const std::filesystem::path& est_path,
                                const EvaluationOptions& options) {
  return evaluate(read_trajectory(gt_path), read_trajectory(est_path), options);
}

}  // namespace stillslam
