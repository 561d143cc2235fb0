#pragma once
// Bundle adjustment over plain structs (map/ converts its keyframes and map
// points): local BA (mapping/) and global BA (loop/) use the same function.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "stillslam/geometry/pinhole_camera.h"
#include "stillslam/optimize/observation_options.h"

namespace stillslam {

struct BaKeyframe {
  std::uint64_t id = 0;  // caller's id, carried through untouched
  Eigen::Isometry3d T_cam_world = Eigen::Isometry3d::Identity();
  bool fixed = false;  // held constant (e.g. covisible keyframes outside the local window)
  // A prior on a free keyframe's camera centre C (world axes): the residual
  // prior_sqrt_info * (C - prior_centre), never robust, in every pass. A zero
  // matrix: none. Not counted in initial_cost / final_cost.
  Eigen::Vector3d prior_centre = Eigen::Vector3d::Zero();
  Eigen::Matrix3d prior_sqrt_info = Eigen::Matrix3d::Zero();
};

struct BaPoint {
  std::uint64_t id = 0;
  Eigen::Vector3d position_world = Eigen::Vector3d::Zero();
};

struct BaObservation {
  std::size_t keyframe = 0;  // index into the keyframe vector
  std::size_t point = 0;     // index into the point vector
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // undistorted
  double u_right = -1;    // >= 0: stereo/RGB-D observation
  double inv_sigma2 = 1;
};

enum class BaLinearSolver { DenseSchur, SparseSchur, IterativeSchur, Auto };

// Ceres, or the hand-written Schur-complement Levenberg-Marquardt of
// schur_bundle_adjuster.h (same residuals, losses and stopping rules; used
// up to kSchurMaxFreeKeyframes free keyframes, Ceres above).
enum class BaSolver { Ceres, Schur };

struct BundleAdjustmentOptions {
  // Levenberg-Marquardt iterations of the first (robust) pass.
  int iterations = 10;
  // After the first pass: flag observations above chi2 (or behind the
  // camera) as outliers, then run outlier_rounds more passes without them and
  // without Huber, re-classifying after each (0 = single pass).
  int outlier_rounds = 1;
  int iterations_after_outliers = 10;
  double chi2_mono = kChi2Mono95;
  double chi2_stereo = kChi2Stereo95;
  bool huber = true;
  // Ceres: 1 thread is bit-for-bit deterministic; more threads may change
  // rounding. The Schur solver always runs on the calling thread.
  int num_threads = 1;
  BaSolver solver = BaSolver::Ceres;
  // Ceres only. Auto: dense Schur up to 40 free keyframes (fastest for local windows,
  // measured in bench/bench_optimize.cpp), sparse Schur (SuiteSparse) above.
  BaLinearSolver linear_solver = BaLinearSolver::Auto;
  // Stereo/RGB-D observations as two 2-row residual blocks (the mono block and
  // the right-image row): with every block the same size Ceres uses its
  // fixed-size SchurEliminator<2, 3, 6>. false: one 3-row block, which sends
  // any problem with mono and stereo observations (or stereo only: Ceres has
  // no <3, 3, 6>) to the dynamic-size eliminator. bench/README.md has both.
  // Both solvers: true puts Huber on the (u, v) pair and on the right-image
  // row apart, false on all three rows together.
  bool split_stereo = true;
  // A pass stops once an iteration lowers the cost by less than this
  // fraction (Ceres' function_tolerance).
  double function_tolerance = 1e-6;
  // Wall-clock budget of each pass in seconds (0: none). Not deterministic.
  double max_seconds_per_pass = 0;
  const std::atomic<bool>* abort = nullptr;  // stop early when set (checked every iteration)
  // When abort stops a pass: true keeps the pass's last accepted iterate (Ceres
  // ends it as converged and writes that state back); false leaves the state
  // the pass started from (Ceres' SOLVER_ABORT).
  bool keep_progress_on_abort = false;
  // Tests: called at every solver iteration (0 = the pass's start state),
  // before abort is read.
  std::function<void()> on_iteration;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

struct BundleAdjustmentResult {
  std::vector<Eigen::Isometry3d> T_cam_world;  // per keyframe (fixed/unobserved ones bit-exact unchanged)
  std::vector<Eigen::Vector3d> points;         // per point
  std::vector<bool> observation_inlier;        // per observation, after the last classification
  double initial_cost = 0;  // 0.5 * sum of squared whitened errors (no robust loss)
  double final_cost = 0;    // same measure, inliers only
  bool aborted = false;  // abort stopped a pass early or kept one from starting
  int iterations = 0;    // solver iterations over all passes (as Ceres counts them)
  // Accepted solver steps whose state is in the result (an aborted pass's
  // steps only with keep_progress_on_abort): 0 after an abort means the
  // BA's work was discarded.
  int applied_steps = 0;
};

// Throws stillslam::Error when an observation indexes outside the vectors.
// Points without observations are returned unchanged.
BundleAdjustmentResult bundle_adjust(const PinholeCamera& camera, std::vector<BaKeyframe> keyframes,
                                     std::vector<BaPoint> points,
                                     const std::vector<BaObservation>& observations,
                                     const BundleAdjustmentOptions& options = {});

}  // namespace stillslam
