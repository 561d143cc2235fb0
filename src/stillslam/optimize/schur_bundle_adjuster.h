#pragma once
// One Levenberg-Marquardt pass of bundle adjustment without Ceres (issue #21):
// the same residuals as reprojection_costs.h (mono [u, v], stereo/RGB-D
// [u, v, u_right], whitened, analytic Jacobians), the same left SE3 update as
// Se3LeftManifold, and Ceres' trust-region rules (initial radius 1e4,
// Nielsen's update, step accepted above a 1e-3 gain ratio, function and
// parameter tolerance, 5 invalid steps in a row fail the pass), so
// bundle_adjust() gives the same answers either way. Per iteration it
// accumulates the pose, pose-point and point blocks, eliminates the points
// (damped 3x3 inverses), solves the reduced camera system over the free
// keyframes with a dense Cholesky and back-substitutes the points. Buffers
// are sized once per pass; the iterations do not allocate.
// Single-threaded: results repeat bit for bit.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "stillslam/optimize/bundle_adjustment.h"
#include "stillslam/optimize/reprojection_costs.h"
#include "stillslam/optimize/se3_manifold.h"

namespace stillslam {

// The dense reduced camera system is used up to this many free keyframes
// (a 384 x 384 Cholesky); bundle_adjust() hands larger problems to Ceres.
inline constexpr int kSchurMaxFreeKeyframes = 64;

// The inverse of a symmetric positive definite 3x3 matrix from its Cholesky
// factor L (lower, as Eigen::LLT::matrixL()): the same operations, in the same
// order, as Eigen 3.4's LLT::solve(Identity) (its triangular solver for
// matrix right-hand sides, column-major L then row-major L^T), so the result
// is bit-identical, without that solver's blocking and packing overhead.
Eigen::Matrix3d inverse_from_cholesky(const Eigen::Matrix3d& L);

struct SchurPassResult {
  int iterations = 0;     // as Ceres counts them (iteration 0 excluded)
  int applied_steps = 0;  // accepted steps written back to the state
  bool aborted = false;   // options.abort stopped the pass
  bool usable = true;     // false: the state was left as the pass found it
};

class SchurBundleAdjuster {
 public:
  // stereo[i]: observation i has a right-image coordinate in use.
  SchurBundleAdjuster(const Intrinsics& k, const std::vector<BaKeyframe>& keyframes,
                      const std::vector<BaObservation>& observations, const std::vector<bool>& stereo);

  // Free keyframes among those with an active observation.
  int free_keyframes(const std::vector<bool>& active) const;

  // Runs one pass over the active observations, robust (Huber, deltas as in
  // bundle_adjustment.cpp) or not, for at most `iterations` iterations.
  // poses/points are updated in place unless the pass ends unusable or is
  // aborted without options.keep_progress_on_abort.
  SchurPassResult run_pass(std::vector<PoseParams>& poses, std::vector<Eigen::Vector3d>& points,
                           const std::vector<bool>& active, bool robust, int iterations,
                           const BundleAdjustmentOptions& options);

 private:
  void setup(const std::vector<bool>& active, std::size_t num_points);
  // Robust cost at (poses, points); false when an active point is not in
  // front of its camera. With `linearize` also fills the blocks and gradient.
  bool evaluate(const std::vector<PoseParams>& poses, const std::vector<Eigen::Vector3d>& points, bool robust,
                bool linearize, double& cost);
  // Solves the damped system for the step; false when a Cholesky fails.
  bool solve(double mu);

  Intrinsics k_;
  const std::vector<BaKeyframe>& keyframes_;
  const std::vector<BaObservation>& observations_;
  const std::vector<bool>& stereo_;
  double huber_mono_, huber_stereo_, huber_right_;  // squared deltas (chi2 units)
  bool split_stereo_ = true;

  // Per pass: free keyframe index (-1: fixed or unused), variable points,
  // active observations grouped by point.
  std::vector<int> pose_index_;
  std::vector<std::size_t> free_poses_;   // keyframe of each free index
  std::vector<int> point_index_;          // -1: unused
  std::vector<std::size_t> used_points_;  // point of each variable index
  std::vector<std::size_t> point_start_;  // CSR over used_points_: observations per point
  std::vector<std::size_t> point_obs_;
  std::vector<int> entry_pose_;           // pose_index_ of each entry's keyframe, per entry of point_obs_

  // Per linearization.
  std::vector<Eigen::Matrix<double, 6, 6>> U_;
  std::vector<Eigen::Matrix<double, 6, 1>> gc_;
  std::vector<Eigen::Matrix3d> V_;
  std::vector<Eigen::Vector3d> gp_;
  std::vector<Eigen::Matrix<double, 6, 3>> W_;  // per entry of point_obs_
  std::vector<Eigen::Matrix<double, 6, 3>> Y_;  // W V^-1, per entry of point_obs_
  std::vector<Eigen::Matrix3d> Vinv_;
  std::vector<Eigen::Matrix3d> R_;  // rotation per keyframe of the state evaluated
  std::vector<std::size_t> used_keyframes_;
  std::vector<PoseParams> cur_poses_, cand_poses_;
  std::vector<Eigen::Vector3d> cur_points_, cand_points_;
  double gradient_max_ = 0;  // max |gradient| entry at the last linearization
  double x_norm_ = 0;        // norm of the free parameters (Ceres' parameter tolerance)
  Eigen::MatrixXd S_;
  Eigen::VectorXd rhs_, dc_;
  std::vector<Eigen::Vector3d> dp_;
  double model_change_ = 0;
  double step_norm2_ = 0;
};

}  // namespace stillslam
