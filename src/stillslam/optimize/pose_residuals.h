#pragma once
// All reprojection residuals of optimize_pose in ONE Ceres residual block.
// The unknown is a plain 6-vector delta = [omega, v] applied on the left of a
// fixed anchor pose, T(delta) = [Exp(omega), v] * T_anchor (re-anchored at the
// current estimate every round). Why one block and no manifold: in Ceres 2.1
// every residual block pays for NaN-initialisation/validation and a manifold
// Jacobian product, which cost several times more than a reprojection; one
// block with an exact analytic Jacobian makes a 600-observation solve several
// times cheaper (bench/bench_optimize.cpp).
//
// The Huber loss is folded into the residual: an observation with whitened
// error norm n > delta returns r * sqrt(2 delta n - delta^2) / n, so the
// squared norm is exactly Ceres' HuberLoss rho(n^2); the Jacobian is the exact
// derivative of that residual, so the minimizer is the Huber M-estimate.
#include <ceres/cost_function.h>
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "stillslam/optimize/pose_optimizer.h"
#include "stillslam/optimize/reprojection_costs.h"

namespace stillslam {

struct PoseResidualsOptions {
  bool robust = true;
  double huber_mono = 2.447;    // sqrt(chi2_mono)
  double huber_stereo = 2.796;  // sqrt(chi2_stereo)
};

class PoseResiduals final : public ceres::CostFunction {
 public:
  // `active` indexes into `observations` (which must outlive this object);
  // stereo[i] selects the 3-row residual for observation i.
  PoseResiduals(const Intrinsics& k, const Eigen::Isometry3d& anchor, const std::vector<PoseObservation>& observations,
                const std::vector<bool>& stereo, std::vector<std::size_t> active, const PoseResidualsOptions& options);
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

  // T(delta) for this block's anchor.
  Eigen::Isometry3d pose(const double* delta) const;

 private:
  Intrinsics k_;
  Eigen::Isometry3d anchor_;
  const std::vector<PoseObservation>& observations_;
  const std::vector<bool>& stereo_;
  std::vector<std::size_t> active_;
  PoseResidualsOptions options_;
};

}  // namespace stillslam
