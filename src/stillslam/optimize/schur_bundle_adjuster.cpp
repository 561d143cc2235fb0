#include "stillslam/optimize/schur_bundle_adjuster.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "stillslam/geometry/se3.h"

namespace stillslam {
namespace schur_ba {

// Ceres' defaults for the trust-region loop (Solver::Options).
constexpr double kInitialRadius = 1e4;
constexpr double kMaxRadius = 1e16;
constexpr double kMinRadius = 1e-32;
constexpr double kMinRelativeDecrease = 1e-3;
constexpr double kMinDiagonal = 1e-6;
constexpr double kMaxDiagonal = 1e32;
constexpr double kGradientTolerance = 1e-10;
constexpr double kParameterTolerance = 1e-8;
constexpr int kMaxConsecutiveInvalidSteps = 5;

// Huber on a squared norm s with squared delta b: rho(s) and rho'(s).
struct Robust {
  double rho, weight;
};
inline Robust huber(double s, double b) {
  if (s <= b) return {s, 1.0};
  const double r = std::sqrt(s);
  return {2.0 * std::sqrt(b) * r - b, std::sqrt(b) / r};
}

inline double clamp_diagonal(double d) { return std::clamp(d, kMinDiagonal, kMaxDiagonal); }

}  // namespace schur_ba

Eigen::Matrix3d inverse_from_cholesky(const Eigen::Matrix3d& L) {
  Eigen::Matrix3d X = Eigen::Matrix3d::Identity();
  // L X = I, column by column: row i scaled by 1 / L(i, i), then eliminated below.
  for (int i = 0; i < 3; ++i) {
    const double a = 1.0 / L(i, i);
    for (int j = 0; j < 3; ++j) {
      X(i, j) *= a;
      const double b = X(i, j);
      for (int r = i + 1; r < 3; ++r) X(r, j) -= b * L(r, i);
    }
  }
  // L^T X = Y, last row first: the dot product over the rows solved so far.
  for (int k = 0; k < 3; ++k) {
    const int i = 2 - k;
    const double a = 1.0 / L(i, i);
    for (int j = 0; j < 3; ++j) {
      double b = 0;
      for (int r = 0; r < k; ++r) b += L(i + 1 + r, i) * X(i + 1 + r, j);
      X(i, j) = (X(i, j) - b) * a;
    }
  }
  return X;
}

SchurBundleAdjuster::SchurBundleAdjuster(const Intrinsics& k, const std::vector<BaKeyframe>& keyframes,
                                         const std::vector<BaObservation>& observations,
                                         const std::vector<bool>& stereo)
    : k_(k), keyframes_(keyframes), observations_(observations), stereo_(stereo) {}

int SchurBundleAdjuster::free_keyframes(const std::vector<bool>& active) const {
  std::vector<bool> seen(keyframes_.size(), false);
  int n = 0;
  for (std::size_t i = 0; i < observations_.size(); ++i) {
    const std::size_t kf = observations_[i].keyframe;
    if (!active[i] || seen[kf]) continue;
    seen[kf] = true;
    if (!keyframes_[kf].fixed) ++n;
  }
  return n;
}

void SchurBundleAdjuster::setup(const std::vector<bool>& active, std::size_t num_points) {
  pose_index_.assign(keyframes_.size(), -1);
  point_index_.assign(num_points, -1);
  free_poses_.clear();
  used_points_.clear();
  used_keyframes_.clear();
  std::vector<bool> keyframe_used(keyframes_.size(), false);
  std::vector<std::size_t> count;
  for (std::size_t i = 0; i < observations_.size(); ++i) {
    if (!active[i]) continue;
    const BaObservation& o = observations_[i];
    if (!keyframe_used[o.keyframe]) {
      keyframe_used[o.keyframe] = true;
      used_keyframes_.push_back(o.keyframe);
      if (!keyframes_[o.keyframe].fixed) {
        pose_index_[o.keyframe] = static_cast<int>(free_poses_.size());
        free_poses_.push_back(o.keyframe);
      }
    }
    if (point_index_[o.point] < 0) {
      point_index_[o.point] = static_cast<int>(used_points_.size());
      used_points_.push_back(o.point);
      count.push_back(0);
    }
    ++count[static_cast<std::size_t>(point_index_[o.point])];
  }
  const std::size_t np = used_points_.size(), nf = free_poses_.size();
  point_start_.assign(np + 1, 0);
  for (std::size_t j = 0; j < np; ++j) point_start_[j + 1] = point_start_[j] + count[j];
  point_obs_.resize(point_start_[np]);
  std::vector<std::size_t> fill(point_start_.begin(), point_start_.end() - 1);
  for (std::size_t i = 0; i < observations_.size(); ++i) {
    if (active[i]) point_obs_[fill[static_cast<std::size_t>(point_index_[observations_[i].point])]++] = i;
  }
  entry_pose_.resize(point_obs_.size());
  for (std::size_t e = 0; e < point_obs_.size(); ++e) {
    entry_pose_[e] = pose_index_[observations_[point_obs_[e]].keyframe];
  }
  U_.resize(nf);
  gc_.resize(nf);
  V_.resize(np);
  gp_.resize(np);
  Vinv_.resize(np);
  dp_.resize(np);
  W_.resize(point_obs_.size());
  Y_.resize(point_obs_.size());
  R_.resize(keyframes_.size());
  S_.resize(static_cast<Eigen::Index>(6 * nf), static_cast<Eigen::Index>(6 * nf));
  rhs_.resize(static_cast<Eigen::Index>(6 * nf));
  dc_.resize(static_cast<Eigen::Index>(6 * nf));
}

bool SchurBundleAdjuster::evaluate(const std::vector<PoseParams>& poses, const std::vector<Eigen::Vector3d>& points,
                                   bool robust, bool linearize, double& cost) {
  using schur_ba::huber;
  for (const std::size_t kf : used_keyframes_) {
    // As reprojection_costs.cpp: the quaternion is unit length, not renormalized.
    R_[kf] = Eigen::Map<const Eigen::Quaterniond>(poses[kf].data()).toRotationMatrix();
  }
  if (linearize) {
    for (auto& m : U_) m.setZero();
    for (auto& g : gc_) g.setZero();
  }
  cost = 0;
  for (std::size_t j = 0; j < used_points_.size(); ++j) {
    const Eigen::Vector3d& X = points[used_points_[j]];
    Eigen::Matrix3d V = Eigen::Matrix3d::Zero();
    Eigen::Vector3d gp = Eigen::Vector3d::Zero();
    for (std::size_t e = point_start_[j]; e < point_start_[j + 1]; ++e) {
      const std::size_t i = point_obs_[e];
      const BaObservation& o = observations_[i];
      const Eigen::Matrix3d& R = R_[o.keyframe];
      const Eigen::Vector3d p = R * X + Eigen::Map<const Eigen::Vector3d>(poses[o.keyframe].data() + 4);
      if (p.z() < kMinCameraDepth) return false;
      const double s = std::sqrt(o.inv_sigma2);
      const double iz = 1.0 / p.z();
      const double u = k_.fx * p.x() * iz + k_.cx;
      Eigen::Vector3d r(s * (u - o.pixel.x()), s * (k_.fy * p.y() * iz + k_.cy - o.pixel.y()), 0.0);
      const bool st = stereo_[i];
      if (st) r.z() = s * (u - k_.bf * iz - o.u_right);
      // Row weights rho' (Ceres' corrector for Huber scales residual and
      // Jacobian rows by sqrt(rho')).
      double w01 = 1, w2 = 1;
      if (!robust) {
        cost += 0.5 * r.squaredNorm();
      } else if (st && !split_stereo_) {
        const auto h = huber(r.squaredNorm(), huber_stereo_);
        cost += 0.5 * h.rho;
        w01 = w2 = h.weight;
      } else {
        const auto h = huber(r.x() * r.x() + r.y() * r.y(), huber_mono_);
        cost += 0.5 * h.rho;
        w01 = h.weight;
        if (st) {
          const auto hr = huber(r.z() * r.z(), huber_right_);
          cost += 0.5 * hr.rho;
          w2 = hr.weight;
        }
      }
      if (!linearize) continue;
      const double s01 = s * std::sqrt(w01), s2 = s * std::sqrt(w2);
      r.head<2>() *= std::sqrt(w01);
      r.z() *= std::sqrt(w2);
      // d(u, v, u_r)/d p_cam, whitened and weighted; the third row is zero for mono.
      Eigen::Matrix3d Jp;
      Jp << s01 * k_.fx * iz, 0, -s01 * k_.fx * p.x() * iz * iz,  //
          0, s01 * k_.fy * iz, -s01 * k_.fy * p.y() * iz * iz,    //
          s2 * k_.fx * iz, 0, s2 * (-k_.fx * p.x() * iz * iz + k_.bf * iz * iz);
      if (!st) Jp.row(2).setZero();
      const Eigen::Matrix3d Jq = Jp * R;  // d/d point
      V.noalias() += Jq.transpose() * Jq;
      gp.noalias() += Jq.transpose() * r;
      const int a = entry_pose_[e];
      if (a < 0) continue;
      Eigen::Matrix<double, 3, 6> Jc;  // d/d [omega, v] of the left update: Jp [-[p]x, I]
      Jc.leftCols<3>().noalias() = -Jp * skew(p);
      Jc.rightCols<3>() = Jp;
      U_[static_cast<std::size_t>(a)].noalias() += Jc.transpose() * Jc;
      gc_[static_cast<std::size_t>(a)].noalias() += Jc.transpose() * r;
      W_[e].noalias() = Jc.transpose() * Jq;
    }
    if (linearize) {
      V_[j] = V;
      gp_[j] = gp;
    }
  }
  // BaKeyframe's centre prior: C = -R^T t moves by -R^T v under the left
  // update, so J = [0, -L R^T].
  for (std::size_t a = 0; a < free_poses_.size(); ++a) {
    const BaKeyframe& b = keyframes_[free_poses_[a]];
    if (b.prior_sqrt_info.isZero()) continue;
    const Eigen::Matrix3d& R = R_[free_poses_[a]];
    const Eigen::Vector3d centre = -(R.transpose() * Eigen::Map<const Eigen::Vector3d>(poses[free_poses_[a]].data() + 4));
    const Eigen::Vector3d r = b.prior_sqrt_info * (centre - b.prior_centre);
    cost += 0.5 * r.squaredNorm();
    if (!linearize) continue;
    const Eigen::Matrix3d Jv = -b.prior_sqrt_info * R.transpose();
    U_[a].bottomRightCorner<3, 3>().noalias() += Jv.transpose() * Jv;
    gc_[a].tail<3>().noalias() += Jv.transpose() * r;
  }
  if (linearize) {
    gradient_max_ = 0;
    double x2 = 0;
    for (const auto& g : gc_) gradient_max_ = std::max(gradient_max_, g.cwiseAbs().maxCoeff());
    for (const auto& g : gp_) gradient_max_ = std::max(gradient_max_, g.cwiseAbs().maxCoeff());
    for (const std::size_t kf : free_poses_) {
      for (const double v : poses[kf]) x2 += v * v;
    }
    for (const std::size_t pt : used_points_) x2 += points[pt].squaredNorm();
    x_norm_ = std::sqrt(x2);
  }
  return true;
}

bool SchurBundleAdjuster::solve(double mu) {
  using schur_ba::clamp_diagonal;
  const std::size_t nf = free_poses_.size();
  S_.setZero();
  for (std::size_t a = 0; a < nf; ++a) rhs_.segment<6>(static_cast<Eigen::Index>(6 * a)) = -gc_[a];
  // Eliminate each point: S -= W V^-1 W^T, rhs += W V^-1 gp (lower block triangle only).
  for (std::size_t j = 0; j < used_points_.size(); ++j) {
    Eigen::Matrix3d Vd = V_[j];
    for (int d = 0; d < 3; ++d) Vd(d, d) += mu * clamp_diagonal(V_[j](d, d));
    const Eigen::LLT<Eigen::Matrix3d> llt(Vd);
    if (llt.info() != Eigen::Success) return false;
    Vinv_[j] = inverse_from_cholesky(llt.matrixL());
    for (std::size_t e = point_start_[j]; e < point_start_[j + 1]; ++e) {
      const int a = entry_pose_[e];
      if (a < 0) continue;
      Y_[e].noalias() = W_[e] * Vinv_[j];
      rhs_.segment<6>(6 * a).noalias() += Y_[e] * gp_[j];
      for (std::size_t f = point_start_[j]; f < point_start_[j + 1]; ++f) {
        const int b = entry_pose_[f];
        if (b < 0 || b > a) continue;
        S_.block<6, 6>(6 * a, 6 * b).noalias() -= Y_[e] * W_[f].transpose();
      }
    }
  }
  for (std::size_t a = 0; a < nf; ++a) {
    Eigen::Matrix<double, 6, 6> Ud = U_[a];
    for (int d = 0; d < 6; ++d) Ud(d, d) += mu * clamp_diagonal(U_[a](d, d));
    S_.block<6, 6>(static_cast<Eigen::Index>(6 * a), static_cast<Eigen::Index>(6 * a)) += Ud;
  }
  if (nf > 0) {
    Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(S_);  // in place, reads the lower triangle
    if (llt.info() != Eigen::Success) return false;
    dc_ = rhs_;
    llt.solveInPlace(dc_);
  }
  // Back-substitution, and the model's cost decrease for the gain ratio:
  // with (H + mu D) dx = -g it is -g.dx - dx.H.dx / 2 = (-g.dx + mu dx.D.dx) / 2.
  double g_dx = 0, damp = 0;
  step_norm2_ = 0;
  for (std::size_t a = 0; a < nf; ++a) {
    const auto dx = dc_.segment<6>(static_cast<Eigen::Index>(6 * a));
    g_dx += gc_[a].dot(dx);
    for (int d = 0; d < 6; ++d) damp += clamp_diagonal(U_[a](d, d)) * dx[d] * dx[d];
    step_norm2_ += dx.squaredNorm();
  }
  for (std::size_t j = 0; j < used_points_.size(); ++j) {
    Eigen::Vector3d b = -gp_[j];
    for (std::size_t e = point_start_[j]; e < point_start_[j + 1]; ++e) {
      const int a = entry_pose_[e];
      if (a >= 0) b.noalias() -= W_[e].transpose() * dc_.segment<6>(6 * a);
    }
    dp_[j].noalias() = Vinv_[j] * b;
    g_dx += gp_[j].dot(dp_[j]);
    for (int d = 0; d < 3; ++d) damp += clamp_diagonal(V_[j](d, d)) * dp_[j][d] * dp_[j][d];
    step_norm2_ += dp_[j].squaredNorm();
  }
  model_change_ = 0.5 * (-g_dx + mu * damp);
  return std::isfinite(model_change_);
}

SchurPassResult SchurBundleAdjuster::run_pass(std::vector<PoseParams>& poses, std::vector<Eigen::Vector3d>& points,
                                              const std::vector<bool>& active, bool robust, int iterations,
                                              const BundleAdjustmentOptions& options) {
  using namespace schur_ba;
  SchurPassResult result;
  split_stereo_ = options.split_stereo;
  huber_mono_ = options.chi2_mono;
  huber_stereo_ = options.chi2_stereo;
  huber_right_ = kChi2OneDof95;
  setup(active, points.size());
  if (point_obs_.empty()) return result;
  const auto start = std::chrono::steady_clock::now();
  cur_poses_ = poses;
  cur_points_ = points;
  cand_poses_ = poses;
  cand_points_ = points;
  double cost = 0;
  if (!evaluate(cur_poses_, cur_points_, robust, true, cost)) {
    result.usable = false;
    return result;
  }
  const Se3LeftManifold manifold;
  double radius = kInitialRadius, decrease_factor = 2;
  int invalid_in_row = 0, iteration = 0, applied = 0;
  bool successful = true;  // iteration 0
  auto write_back = [&] {
    for (const std::size_t kf : free_poses_) poses[kf] = cur_poses_[kf];
    for (const std::size_t pt : used_points_) points[pt] = cur_points_[pt];
  };
  while (true) {
    // The end of an iteration, in Ceres' order: count, callback, stop tests.
    if (iteration > 0) {
      ++result.iterations;
      if (successful) ++applied;
    }
    if (options.on_iteration) options.on_iteration();
    if (options.abort && options.abort->load()) {
      result.aborted = true;
      if (options.keep_progress_on_abort) {
        write_back();
        result.applied_steps = applied;
      } else {
        result.usable = false;
      }
      return result;
    }
    if (options.max_seconds_per_pass > 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > options.max_seconds_per_pass) {
      break;
    }
    if (iteration >= iterations || gradient_max_ <= kGradientTolerance || radius <= kMinRadius) break;
    ++iteration;

    const double mu = 1.0 / radius;
    if (!solve(mu) || !(model_change_ > 0)) {
      if (++invalid_in_row >= kMaxConsecutiveInvalidSteps) {
        result.usable = false;  // Ceres ends the solve as FAILURE
        return result;
      }
      radius /= decrease_factor;
      decrease_factor *= 2;
      successful = false;
      continue;
    }
    invalid_in_row = 0;
    for (std::size_t a = 0; a < free_poses_.size(); ++a) {
      const std::size_t kf = free_poses_[a];
      manifold.Plus(cur_poses_[kf].data(), dc_.data() + 6 * a, cand_poses_[kf].data());
    }
    for (std::size_t j = 0; j < used_points_.size(); ++j) {
      cand_points_[used_points_[j]] = cur_points_[used_points_[j]] + dp_[j];
    }
    double cand_cost = 0;
    if (!evaluate(cand_poses_, cand_points_, robust, false, cand_cost)) cand_cost = std::numeric_limits<double>::max();
    if (std::sqrt(step_norm2_) <= kParameterTolerance * (x_norm_ + kParameterTolerance)) break;
    if (std::abs(cost - cand_cost) <= options.function_tolerance * cost) break;
    const double relative_decrease = (cost - cand_cost) / model_change_;
    if (relative_decrease > kMinRelativeDecrease) {
      std::swap(cur_poses_, cand_poses_);
      std::swap(cur_points_, cand_points_);
      if (!evaluate(cur_poses_, cur_points_, robust, true, cost)) {
        result.usable = false;
        return result;
      }
      const double q = 2.0 * relative_decrease - 1.0;
      radius = std::min(kMaxRadius, radius / std::max(1.0 / 3.0, 1.0 - q * q * q));
      decrease_factor = 2;
      successful = true;
    } else {
      radius /= decrease_factor;
      decrease_factor *= 2;
      successful = false;
    }
  }
  write_back();
  result.applied_steps = applied;
  return result;
}

}  // namespace stillslam
