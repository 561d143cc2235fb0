#pragma once
// SE3 pose-graph optimization (essential graph after a loop closure).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace stillslam {

struct PoseGraphEdge {
  std::size_t from = 0, to = 0;  // node indices
  // Measured relative pose: T_world_from^-1 * T_world_to.
  Eigen::Isometry3d T_from_to = Eigen::Isometry3d::Identity();
  double weight = 1;  // scales the whole 6-dof residual
};

// Returns the optimized T_world_node for every node; fixed nodes keep their
// input pose. The residual of an edge is weight * [angle-axis, translation] of
// E = T_from_to^-1 * T_from^-1 * T_to (rotation first). Throws stillslam::Error
// when an edge or fixed index is out of range.
std::vector<Eigen::Isometry3d> optimize_pose_graph(std::vector<Eigen::Isometry3d> T_world_node,
                                                   const std::vector<PoseGraphEdge>& edges,
                                                   const std::vector<std::size_t>& fixed_nodes,
                                                   int iterations = 20);

}  // namespace stillslam
