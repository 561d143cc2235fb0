#include "stillslam/optimize/bundle_adjustment.h"

#include <ceres/iteration_callback.h>
#include <ceres/loss_function.h>
#include <ceres/ordered_groups.h>
#include <ceres/problem.h>
#include <ceres/solver.h>
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "stillslam/core/check.h"
#include "stillslam/core/error.h"
#include "stillslam/core/option_check.h"
#include "stillslam/optimize/reprojection_costs.h"
#include "stillslam/optimize/schur_bundle_adjuster.h"
#include "stillslam/optimize/se3_manifold.h"

namespace stillslam {
namespace {

// Stops the solve once the abort flag is set: as converged (Ceres writes the
// best accepted iterate back) or as failed (Ceres keeps the start state).
class AbortCallback final : public ceres::IterationCallback {
 public:
  explicit AbortCallback(const BundleAdjustmentOptions& options) : options_(options) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    if (options_.on_iteration) options_.on_iteration();
    if (!options_.abort || !options_.abort->load()) return ceres::SOLVER_CONTINUE;
    fired = true;
    return options_.keep_progress_on_abort ? ceres::SOLVER_TERMINATE_SUCCESSFULLY : ceres::SOLVER_ABORT;
  }
  bool fired = false;  // stopped the current pass

 private:
  const BundleAdjustmentOptions& options_;
};

// BaKeyframe's centre prior on the 7-parameter pose: C = -R^T t, and under
// the left update [Exp(omega), v] * T the centre moves by -R^T v (omega
// leaves it), so the tangent Jacobian is [0, -L R^T] (column 7 zero, as
// se3_manifold.h asks).
class CentrePriorCost final : public ceres::SizedCostFunction<3, 7> {
 public:
  CentrePriorCost(const Eigen::Vector3d& centre, const Eigen::Matrix3d& sqrt_info)
      : centre_(centre), sqrt_info_(sqrt_info) {}
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Matrix3d R = Eigen::Map<const Eigen::Quaterniond>(parameters[0]).toRotationMatrix();
    const Eigen::Vector3d t(parameters[0][4], parameters[0][5], parameters[0][6]);
    Eigen::Map<Eigen::Vector3d> r(residuals);
    r = sqrt_info_ * (-(R.transpose() * t) - centre_);
    if (jacobians && jacobians[0]) {
      Eigen::Map<Eigen::Matrix<double, 3, 7, Eigen::RowMajor>> J(jacobians[0]);
      J.setZero();
      J.block<3, 3>(0, 3) = -sqrt_info_ * R.transpose();
    }
    return true;
  }

 private:
  Eigen::Vector3d centre_;
  Eigen::Matrix3d sqrt_info_;
};

// Dense Schur is fastest while the reduced camera system is small.
constexpr int kDenseSchurMaxFreeKeyframes = 40;

}  // namespace

BundleAdjustmentResult bundle_adjust(const PinholeCamera& camera, std::vector<BaKeyframe> keyframes,
                                     std::vector<BaPoint> points, const std::vector<BaObservation>& observations,
                                     const BundleAdjustmentOptions& options) {
  for (std::size_t i = 0; i < observations.size(); ++i) {
    STILLSLAM_CHECK_LT(observations[i].keyframe, keyframes.size(),
                       "bundle_adjust: observation " + std::to_string(i) + " refers to a keyframe it was not given");
    STILLSLAM_CHECK_LT(observations[i].point, points.size(),
                       "bundle_adjust: observation " + std::to_string(i) + " refers to a point it was not given");
  }
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    STILLSLAM_CHECK(keyframes[i].T_cam_world.matrix().allFinite(),
                    "bundle_adjust: keyframe " + std::to_string(i) + " has a non-finite pose");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    STILLSLAM_CHECK(points[i].position_world.allFinite(),
                    "bundle_adjust: point " + std::to_string(i) + " has a non-finite position");
  }
  const Intrinsics k(camera);
  const std::size_t n_obs = observations.size();

  std::vector<PoseParams> poses(keyframes.size());
  for (std::size_t i = 0; i < keyframes.size(); ++i) poses[i] = to_pose_params(keyframes[i].T_cam_world);
  std::vector<Eigen::Vector3d> xyz(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) xyz[i] = points[i].position_world;

  // Keyframes that take part in some pass; the others come back bit-exact.
  std::vector<bool> keyframe_moved(keyframes.size(), false);
  std::vector<bool> stereo(n_obs);
  for (std::size_t i = 0; i < n_obs; ++i) stereo[i] = observations[i].u_right >= 0 && k.bf > 0;
  // costs: the whole observation (or, split, its left-image part); right_costs:
  // the right-image row of a split stereo observation. Made by the first pass
  // that goes to Ceres (the Schur passes do not use them).
  std::vector<std::unique_ptr<ceres::CostFunction>> costs, right_costs, prior_costs;
  auto make_costs = [&] {
    if (!costs.empty()) return;
    prior_costs.resize(keyframes.size());
    for (std::size_t i = 0; i < keyframes.size(); ++i) {
      if (!keyframes[i].fixed && !keyframes[i].prior_sqrt_info.isZero()) {
        prior_costs[i] = std::make_unique<CentrePriorCost>(keyframes[i].prior_centre, keyframes[i].prior_sqrt_info);
      }
    }
    costs.resize(n_obs);
    right_costs.resize(n_obs);
    for (std::size_t i = 0; i < n_obs; ++i) {
      const BaObservation& o = observations[i];
      if (stereo[i] && !options.split_stereo) {
        costs[i] = std::make_unique<StereoBaCost>(k, o.pixel, o.u_right, o.inv_sigma2);
      } else {
        costs[i] = std::make_unique<MonoBaCost>(k, o.pixel, o.inv_sigma2);
      }
      if (stereo[i] && options.split_stereo) {
        right_costs[i] = std::make_unique<StereoRightBaCost>(k, o.u_right, o.inv_sigma2);
      }
    }
  };

  BundleAdjustmentResult result;
  result.observation_inlier.assign(n_obs, false);

  // The poses as transforms, converted once per keyframe (not per observation).
  std::vector<Eigen::Isometry3d> T_cam_world(keyframes.size());
  auto convert_poses = [&] {
    for (std::size_t i = 0; i < keyframes.size(); ++i) T_cam_world[i] = from_pose_params(poses[i].data());
  };
  // Classifies every observation against the current state; returns the
  // cost 0.5 * sum chi2 over the inliers (or over all evaluable ones).
  auto classify = [&](bool all_count) {
    convert_poses();
    double cost = 0;
    for (std::size_t i = 0; i < n_obs; ++i) {
      const BaObservation& o = observations[i];
      const ReprojectionCheck c = check_reprojection(k, T_cam_world[o.keyframe], xyz[o.point],
                                                     o.pixel, stereo[i] ? o.u_right : -1.0, o.inv_sigma2);
      const bool in_front = c.in_front();
      result.observation_inlier[i] = in_front && c.chi2 <= (stereo[i] ? options.chi2_stereo : options.chi2_mono);
      if (result.observation_inlier[i] || (all_count && in_front)) cost += 0.5 * c.chi2;
    }
    return cost;
  };
  result.initial_cost = classify(true);
  // First pass: every observation in front of its camera takes part.
  std::vector<bool> active(n_obs);
  for (std::size_t i = 0; i < n_obs; ++i) {
    const BaObservation& o = observations[i];
    active[i] = (T_cam_world[o.keyframe] * xyz[o.point]).z() >= kMinCameraDepth;
  }

  ceres::HuberLoss huber_mono(std::sqrt(options.chi2_mono));
  ceres::HuberLoss huber_stereo(std::sqrt(options.chi2_stereo));
  ceres::HuberLoss huber_right(std::sqrt(kChi2OneDof95));
  Se3LeftManifold manifold;
  AbortCallback abort_callback(options);

  SchurBundleAdjuster schur(k, keyframes, observations, stereo);

  auto run_pass = [&](bool robust, int iterations) {
    for (std::size_t i = 0; i < n_obs; ++i) {
      if (active[i] && !keyframes[observations[i].keyframe].fixed) keyframe_moved[observations[i].keyframe] = true;
    }
    if (options.solver == BaSolver::Schur && schur.free_keyframes(active) <= kSchurMaxFreeKeyframes) {
      const SchurPassResult r = schur.run_pass(poses, xyz, active, robust, iterations, options);
      result.iterations += r.iterations;
      if (r.aborted) result.aborted = true;
      if (r.usable) result.applied_steps += r.applied_steps;
      return;
    }
    make_costs();
    ceres::Problem::Options problem_options;
    problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options.disable_all_safety_checks = true;
    ceres::Problem problem(problem_options);
    auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
    std::vector<bool> pose_added(keyframes.size(), false), point_added(points.size(), false);
    int free_keyframes = 0;
    for (std::size_t i = 0; i < n_obs; ++i) {
      if (!active[i]) continue;
      const BaObservation& o = observations[i];
      double* pose = poses[o.keyframe].data();
      double* point = xyz[o.point].data();
      if (!pose_added[o.keyframe]) {
        pose_added[o.keyframe] = true;
        problem.AddParameterBlock(pose, 7, &manifold);
        if (keyframes[o.keyframe].fixed) {
          problem.SetParameterBlockConstant(pose);
        } else {
          ++free_keyframes;
          if (prior_costs[o.keyframe]) problem.AddResidualBlock(prior_costs[o.keyframe].get(), nullptr, pose);
        }
        ordering->AddElementToGroup(pose, 1);
      }
      if (!point_added[o.point]) {
        point_added[o.point] = true;
        problem.AddParameterBlock(point, 3);
        ordering->AddElementToGroup(point, 0);
      }
      const bool three_rows = stereo[i] && !options.split_stereo;
      ceres::LossFunction* loss = robust ? (three_rows ? &huber_stereo : &huber_mono) : nullptr;
      problem.AddResidualBlock(costs[i].get(), loss, pose, point);
      if (right_costs[i]) problem.AddResidualBlock(right_costs[i].get(), robust ? &huber_right : nullptr, pose, point);
    }
    if (problem.NumResidualBlocks() == 0) return;

    ceres::Solver::Options solver_options;
    const bool dense = options.linear_solver == BaLinearSolver::DenseSchur ||
                       (options.linear_solver == BaLinearSolver::Auto && free_keyframes <= kDenseSchurMaxFreeKeyframes);
    solver_options.linear_solver_type = dense ? ceres::DENSE_SCHUR : ceres::SPARSE_SCHUR;
    if (options.linear_solver == BaLinearSolver::IterativeSchur) {
      solver_options.linear_solver_type = ceres::ITERATIVE_SCHUR;
      solver_options.preconditioner_type = ceres::SCHUR_JACOBI;
    }
    solver_options.linear_solver_ordering = ordering;
    solver_options.max_num_iterations = iterations;
    solver_options.function_tolerance = options.function_tolerance;
    if (options.max_seconds_per_pass > 0) solver_options.max_solver_time_in_seconds = options.max_seconds_per_pass;
    solver_options.num_threads = std::max(1, options.num_threads);
    solver_options.logging_type = ceres::SILENT;
    solver_options.minimizer_progress_to_stdout = false;
    if (options.abort || options.on_iteration) solver_options.callbacks.push_back(&abort_callback);
    abort_callback.fired = false;
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options, &problem, &summary);
    // Entry 0 of summary.iterations is the initial state.
    result.iterations += std::max(0, static_cast<int>(summary.iterations.size()) - 1);
    if (abort_callback.fired) result.aborted = true;
    if (summary.IsSolutionUsable()) {
      for (std::size_t it = 1; it < summary.iterations.size(); ++it) {
        if (summary.iterations[it].step_is_successful) ++result.applied_steps;
      }
    }
  };

  // A pass is not started once the flag is set.
  auto stop = [&] {
    if (options.abort && options.abort->load()) result.aborted = true;
    return result.aborted;
  };
  if (!stop()) run_pass(options.huber, options.iterations);
  classify(false);
  for (int round = 0; round < options.outlier_rounds && !stop(); ++round) {
    active = result.observation_inlier;
    run_pass(false, options.iterations_after_outliers);
    classify(false);
  }
  result.final_cost = classify(false);

  result.T_cam_world.resize(keyframes.size());
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    // Fixed and unobserved keyframes are returned bit-exact (no quaternion round trip).
    result.T_cam_world[i] = keyframe_moved[i] ? from_pose_params(poses[i].data()) : keyframes[i].T_cam_world;
  }
  result.points = std::move(xyz);
  return result;
}

void BundleAdjustmentOptions::check() const {
  using namespace option_check;
  at_least("BundleAdjustmentOptions.iterations", iterations, 1);
  at_least("BundleAdjustmentOptions.outlier_rounds", outlier_rounds, 0);
  at_least("BundleAdjustmentOptions.iterations_after_outliers", iterations_after_outliers, 0);
  above("BundleAdjustmentOptions.chi2_mono", chi2_mono, 0);
  above("BundleAdjustmentOptions.chi2_stereo", chi2_stereo, 0);
  at_least("BundleAdjustmentOptions.num_threads", num_threads, 1);
  at_least("BundleAdjustmentOptions.function_tolerance", function_tolerance, 0.0);
  at_least("BundleAdjustmentOptions.max_seconds_per_pass", max_seconds_per_pass, 0.0);
}

}  // namespace stillslam
