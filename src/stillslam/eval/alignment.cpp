#include "stillslam/eval/alignment.h"

#include <Eigen/Geometry>
#include <cmath>

#include "stillslam/core/check.h"
#include "stillslam/core/error.h"

namespace stillslam {

AlignmentType parse_alignment_type(const std::string& name) {
  if (name == "none") return AlignmentType::None;
  if (name == "se3" || name == "SE3") return AlignmentType::Se3;
  if (name == "sim3" || name == "Sim3") return AlignmentType::Sim3;
  throw Error("unknown alignment '" + name + "'; use se3 (rigid), sim3 (rigid + scale, monocular) or none");
}

std::string to_string(AlignmentType type) {
  switch (type) {
    case AlignmentType::None: return "none";
    case AlignmentType::Se3: return "se3";
    case AlignmentType::Sim3: return "sim3";
  }
  return "none";
}

Eigen::Isometry3d Alignment::apply(const Eigen::Isometry3d& T_world_cam) const {
  Eigen::Isometry3d aligned = Eigen::Isometry3d::Identity();
  aligned.linear() = rotation * T_world_cam.linear();
  aligned.translation() = apply(Eigen::Vector3d(T_world_cam.translation()));
  return aligned;
}

Alignment align_positions(const Eigen::Matrix3Xd& est, const Eigen::Matrix3Xd& gt, AlignmentType type) {
  Alignment alignment;
  alignment.type = type;
  if (type == AlignmentType::None) return alignment;
  STILLSLAM_CHECK_EQ(est.cols(), gt.cols(), "align_positions: pass one ground-truth position per estimated one");
  if (est.cols() < 3) {
    throw Error("alignment needs at least 3 associated poses, got " + std::to_string(est.cols()) +
                "; check the timestamps (--max-dt) or use --align none");
  }
  // A trajectory that never moves has no defined rotation or scale.
  const Eigen::Vector3d mean = est.rowwise().mean();
  const double spread = (est.colwise() - mean).squaredNorm() / static_cast<double>(est.cols());
  if (!(spread > 1e-18)) {
    throw Error("the estimated trajectory does not move, so it cannot be aligned; use --align none");
  }
  const Eigen::Matrix4d T = Eigen::umeyama(est, gt, type == AlignmentType::Sim3);
  const Eigen::Matrix3d sR = T.topLeftCorner<3, 3>();
  alignment.scale = type == AlignmentType::Sim3 ? std::cbrt(sR.determinant()) : 1.0;
  alignment.rotation = sR / alignment.scale;
  alignment.translation = T.topRightCorner<3, 1>();
  return alignment;
}

}  // namespace stillslam
