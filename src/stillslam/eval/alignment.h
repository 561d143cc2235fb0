#pragma once
// Least-squares alignment of estimated positions onto ground truth
// (Umeyama 1991; equals Horn's closed form for the rigid case).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace stillslam {

enum class AlignmentType { None, Se3, Sim3 };

AlignmentType parse_alignment_type(const std::string& name);  // "none", "se3", "sim3"
std::string to_string(AlignmentType type);

// p_gt ≈ scale * rotation * p_est + translation.
struct Alignment {
  AlignmentType type = AlignmentType::None;
  double scale = 1;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d apply(const Eigen::Vector3d& p_est) const { return scale * (rotation * p_est) + translation; }
  // The pose moved into the ground-truth frame; scale affects the position only.
  Eigen::Isometry3d apply(const Eigen::Isometry3d& T_world_cam) const;
};

// Fits the alignment over corresponding columns of `est` and `gt` (3xN).
// Error when there are too few points (SE3/Sim3 need 3) or they are degenerate.
Alignment align_positions(const Eigen::Matrix3Xd& est, const Eigen::Matrix3Xd& gt, AlignmentType type);

}  // namespace stillslam
