#include "stillslam/optimize/pose_optimizer.h"

#include <ceres/problem.h>
#include <ceres/solver.h>
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "stillslam/core/check.h"
#include "stillslam/core/option_check.h"
#include "stillslam/optimize/pose_residuals.h"
#include "stillslam/optimize/reprojection_costs.h"

namespace stillslam {

PoseOptimizationResult optimize_pose(const PinholeCamera& camera, const Eigen::Isometry3d& T_cam_world_init,
                                     const std::vector<PoseObservation>& observations,
                                     const PoseOptimizerOptions& options, const PosePrior* prior) {
  STILLSLAM_CHECK(T_cam_world_init.matrix().allFinite(), "optimize_pose: the initial pose is not finite");
  const Intrinsics k(camera);
  const std::size_t n = observations.size();
  PoseOptimizationResult result;
  result.T_cam_world = T_cam_world_init;
  result.inlier.assign(n, true);
  if (n == 0) return result;

  std::vector<bool> stereo(n);
  for (std::size_t i = 0; i < n; ++i) stereo[i] = observations[i].u_right >= 0 && k.bf > 0;

  auto classify = [&](const Eigen::Isometry3d& T) {
    int inliers = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const PoseObservation& o = observations[i];
      const ReprojectionCheck c =
          check_reprojection(k, T, o.point_world, o.pixel, stereo[i] ? o.u_right : -1.0, o.inv_sigma2);
      result.inlier[i] = c.in_front() && c.chi2 <= (stereo[i] ? options.chi2_stereo : options.chi2_mono);
      inliers += result.inlier[i];
    }
    return inliers;
  };

  // Points behind the initial pose cannot be evaluated; everything else
  // starts as an inlier (the Huber loss bounds the first round's outliers).
  for (std::size_t i = 0; i < n; ++i) {
    result.inlier[i] = (T_cam_world_init * observations[i].point_world).z() >= kMinCameraDepth;
  }

  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;  // cheaper than QR for 6 unknowns
  solver_options.max_num_iterations = options.iterations_per_round;
  solver_options.logging_type = ceres::SILENT;
  solver_options.minimizer_progress_to_stdout = false;
  solver_options.num_threads = 1;

  PoseResidualsOptions residual_options;
  residual_options.huber_mono = std::sqrt(options.chi2_mono);
  residual_options.huber_stereo = std::sqrt(options.chi2_stereo);

  Eigen::Isometry3d T = T_cam_world_init;
  const int rounds = std::max(1, options.rounds);
  for (int round = 0; round < rounds; ++round) {
    std::vector<std::size_t> active;
    for (std::size_t i = 0; i < n; ++i) {
      if (result.inlier[i]) active.push_back(i);
    }
    // Fewer than 3 points cannot fix 6 dof; keep the current estimate.
    if (active.size() < 3) break;
    residual_options.robust = options.huber && round + 1 < rounds;
    // `params` is the delta around T (see pose_residuals.h).
    const auto residuals =
        std::make_unique<PoseResiduals>(k, T, observations, stereo, std::move(active), residual_options);
    double params[6] = {0, 0, 0, 0, 0, 0};
    const std::unique_ptr<ceres::CostFunction> prior_cost(prior ? make_pose_prior_cost(T, *prior) : nullptr);
    ceres::Problem::Options problem_options;
    problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(problem_options);
    problem.AddResidualBlock(residuals.get(), nullptr, params);
    if (prior_cost) problem.AddResidualBlock(prior_cost.get(), nullptr, params);
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options, &problem, &summary);
    T = residuals->pose(params);
    result.num_inliers = classify(T);
    if (result.num_inliers < 10) break;
  }
  result.T_cam_world = T;
  result.num_inliers = classify(T);
  return result;
}

void PoseOptimizerOptions::check() const {
  using namespace option_check;
  at_least("PoseOptimizerOptions.rounds", rounds, 1);
  at_least("PoseOptimizerOptions.iterations_per_round", iterations_per_round, 1);
  above("PoseOptimizerOptions.chi2_mono", chi2_mono, 0);
  above("PoseOptimizerOptions.chi2_stereo", chi2_stereo, 0);
}

}  // namespace stillslam
