#pragma once
// Absolute and relative pose errors over associated, aligned pose sequences
// (gt[k] and est[k] belong to the same instant).
#include <vector>

#include "stillslam/eval/pose_pairs.h"
#include "stillslam/io/trajectory.h"

namespace stillslam {

// |t_gt - t_est| per pose, metres.
std::vector<double> absolute_translation_errors(const Trajectory& gt, const Trajectory& est);

struct RelativeErrors {
  std::vector<double> translation;    // metres
  std::vector<double> rotation_deg;   // degrees
};

// For each pair (i, j): E = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j) with Q ground truth and
// P estimate; translation error |t(E)|, rotation error the angle of R(E).
RelativeErrors relative_errors(const Trajectory& gt, const Trajectory& est, const std::vector<PosePair>& pairs);

// Rotation angle in degrees, robust near 0 and 180 degrees.
double rotation_angle_deg(const Eigen::Matrix3d& R);

}  // namespace stillslam
