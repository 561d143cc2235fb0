#include "stillslam/optimize/pose_prior.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/rotation.h>
#include <cmath>

#include "stillslam/core/option_check.h"

namespace stillslam {

namespace {

// With T(delta) = [Exp(w), v] * anchor:
//   R(delta) R_mean^T = Exp(w) (R_anchor R_mean^T)
//   centre(delta) = centre(anchor) - R_anchor^T Exp(-w) v
struct PosePriorFunctor {
  Eigen::Matrix3d R_anchor_mean;  // R_anchor * R_mean^T
  Eigen::Matrix3d R_anchor_t;     // R_anchor^T
  Eigen::Vector3d centre_offset;  // centre(anchor) - centre(mean)
  double inv_sigma_t, inv_sigma_r, dead_zone;

  template <typename T>
  bool operator()(const T* delta, T* residual) const {
    // Rotation: the rotation vector of Exp(w) * R_anchor_mean.
    T exp_w[9];
    ceres::AngleAxisToRotationMatrix(delta, exp_w);  // column-major
    T product[9];
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) {
        T sum = T(0);
        for (int k = 0; k < 3; ++k) sum += exp_w[k * 3 + r] * R_anchor_mean(k, c);
        product[c * 3 + r] = sum;
      }
    }
    T rotation[3];
    ceres::RotationMatrixToAngleAxis(product, rotation);
    for (int i = 0; i < 3; ++i) residual[i] = rotation[i] * inv_sigma_r;

    // Translation: the camera-centre offset from the mean.
    const T minus_w[3] = {-delta[0], -delta[1], -delta[2]};
    T rotated_v[3];
    ceres::AngleAxisRotatePoint(minus_w, delta + 3, rotated_v);
    T offset[3];
    for (int r = 0; r < 3; ++r) {
      T sum = T(centre_offset(r));
      for (int k = 0; k < 3; ++k) sum -= R_anchor_t(r, k) * rotated_v[k];
      offset[r] = sum;
    }
    T scale = T(inv_sigma_t);
    if (dead_zone > 0) {
      const T norm2 = offset[0] * offset[0] + offset[1] * offset[1] + offset[2] * offset[2];
      if (norm2 <= T(dead_zone * dead_zone)) {
        scale = T(0);
      } else {
        using std::sqrt;
        const T norm = sqrt(norm2);
        scale = (norm - T(dead_zone)) / norm * T(inv_sigma_t);
      }
    }
    for (int r = 0; r < 3; ++r) residual[3 + r] = offset[r] * scale;
    return true;
  }
};

}  // namespace

Eigen::Vector3d camera_centre(const Eigen::Isometry3d& T_cam_world) {
  return -(T_cam_world.linear().transpose() * T_cam_world.translation());
}

ceres::CostFunction* make_pose_prior_cost(const Eigen::Isometry3d& anchor, const PosePrior& prior) {
  prior.check();
  auto* functor = new PosePriorFunctor{anchor.linear() * prior.T_cam_world.linear().transpose(),
                                       anchor.linear().transpose(),
                                       camera_centre(anchor) - camera_centre(prior.T_cam_world),
                                       1.0 / prior.sigma_translation,
                                       1.0 / prior.sigma_rotation,
                                       prior.dead_zone};
  return new ceres::AutoDiffCostFunction<PosePriorFunctor, 6, 6>(functor);
}

void PosePrior::check() const {
  using namespace option_check;
  above("PosePrior.sigma_translation", sigma_translation, 0);
  above("PosePrior.sigma_rotation", sigma_rotation, 0);
  at_least("PosePrior.dead_zone", dead_zone, 0);
}

}  // namespace stillslam
