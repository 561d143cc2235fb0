#include "stillslam/optimize/pose_optimizer.h"

#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>
#include <cmath>
#include <memory>

#include "stillslam/optimize/reprojection_costs.h"
#include "stillslam/optimize/se3_manifold.h"

namespace stillslam {

PoseOptimizationResult optimize_pose(const PinholeCamera& camera, const Eigen::Isometry3d& T_cam_world_init,
                                     const std::vector<PoseObservation>& observations,
                                     const PoseOptimizerOptions& options) {
  const Intrinsics k(camera);
  const std::size_t n = observations.size();
  PoseOptimizationResult result;
  result.T_cam_world = T_cam_world_init;
  result.inlier.assign(n, true);
  if (n == 0) return result;

  // Cost functions are built once and shared by every round's problem.
  std::vector<std::unique_ptr<ceres::CostFunction>> costs(n);
  std::vector<bool> stereo(n);
  for (std::size_t i = 0; i < n; ++i) {
    const PoseObservation& o = observations[i];
    stereo[i] = o.u_right >= 0 && k.bf > 0;
    if (stereo[i]) {
      costs[i] = std::make_unique<StereoPoseCost>(k, o.point_world, o.pixel, o.u_right, o.inv_sigma2);
    } else {
      costs[i] = std::make_unique<MonoPoseCost>(k, o.point_world, o.pixel, o.inv_sigma2);
    }
  }
  ceres::HuberLoss huber_mono(std::sqrt(options.chi2_mono));
  ceres::HuberLoss huber_stereo(std::sqrt(options.chi2_stereo));
  Se3LeftManifold manifold;

  auto classify = [&](const Eigen::Isometry3d& T) {
    int inliers = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const PoseObservation& o = observations[i];
      const ReprojectionCheck c =
          check_reprojection(k, T, o.point_world, o.pixel, stereo[i] ? o.u_right : -1.0, o.inv_sigma2);
      result.inlier[i] = c.depth > 0 && c.chi2 <= (stereo[i] ? options.chi2_stereo : options.chi2_mono);
      inliers += result.inlier[i];
    }
    return inliers;
  };

  // Points behind the initial pose cannot be evaluated; everything else
  // starts as an inlier (the Huber loss bounds the first round's outliers).
  for (std::size_t i = 0; i < n; ++i) {
    result.inlier[i] = (T_cam_world_init * observations[i].point_world).z() > 0;
  }

  PoseParams pose = to_pose_params(T_cam_world_init);
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  solver_options.max_num_iterations = options.iterations_per_round;
  solver_options.logging_type = ceres::SILENT;
  solver_options.minimizer_progress_to_stdout = false;
  solver_options.num_threads = 1;

  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.enable_fast_removal = false;
  problem_options.disable_all_safety_checks = true;

  const int rounds = std::max(1, options.rounds);
  for (int round = 0; round < rounds; ++round) {
    const bool robust = options.huber && round + 1 < rounds;
    ceres::Problem problem(problem_options);
    problem.AddParameterBlock(pose.data(), 7, &manifold);
    int used = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (!result.inlier[i]) continue;
      ceres::LossFunction* loss = robust ? (stereo[i] ? &huber_stereo : &huber_mono) : nullptr;
      problem.AddResidualBlock(costs[i].get(), loss, pose.data());
      ++used;
    }
    // Fewer than 3 points cannot fix 6 dof; keep the current estimate.
    if (used < 3) break;
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options, &problem, &summary);
    result.num_inliers = classify(from_pose_params(pose.data()));
    if (result.num_inliers < 10) break;
  }
  result.T_cam_world = from_pose_params(pose.data());
  result.num_inliers = classify(result.T_cam_world);
  return result;
}

}  // namespace stillslam
