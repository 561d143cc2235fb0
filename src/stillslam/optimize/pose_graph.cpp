#include "stillslam/optimize/pose_graph.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/manifold.h>
#include <ceres/problem.h>
#include <ceres/rotation.h>
#include <ceres/solver.h>
#include <string>

#include "stillslam/core/check.h"

namespace stillslam {
namespace {

// Nodes are stored as T_world_node: quaternion (Eigen x, y, z, w) + translation.
struct RelativePoseError {
  RelativePoseError(const Eigen::Isometry3d& T_from_to, double weight)
      : q_meas_inv(Eigen::Quaterniond(T_from_to.linear()).normalized().conjugate()),
        t_meas(T_from_to.translation()),
        weight(weight) {}

  template <typename T>
  bool operator()(const T* q_from_p, const T* t_from_p, const T* q_to_p, const T* t_to_p, T* residual) const {
    using Quat = Eigen::Quaternion<T>;
    using Vec3 = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Quat> q_from(q_from_p), q_to(q_to_p);
    const Eigen::Map<const Vec3> t_from(t_from_p), t_to(t_to_p);
    const Quat q_from_inv = q_from.conjugate();
    const Quat q_rel = q_from_inv * q_to;
    const Vec3 t_rel = q_from_inv * (t_to - t_from);
    // E = T_meas^-1 * T_rel.
    const Quat q_meas_inv_t = q_meas_inv.template cast<T>();
    const Quat q_err = q_meas_inv_t * q_rel;
    const Vec3 t_err = q_meas_inv_t * (t_rel - t_meas.template cast<T>());
    const T wxyz[4] = {q_err.w(), q_err.x(), q_err.y(), q_err.z()};
    ceres::QuaternionToAngleAxis(wxyz, residual);
    for (int i = 0; i < 3; ++i) {
      residual[i] *= T(weight);
      residual[3 + i] = T(weight) * t_err[i];
    }
    return true;
  }

  Eigen::Quaterniond q_meas_inv;
  Eigen::Vector3d t_meas;
  double weight;
};

}  // namespace

std::vector<Eigen::Isometry3d> optimize_pose_graph(std::vector<Eigen::Isometry3d> T_world_node,
                                                   const std::vector<PoseGraphEdge>& edges,
                                                   const std::vector<std::size_t>& fixed_nodes, int iterations) {
  const std::size_t n = T_world_node.size();
  for (const PoseGraphEdge& e : edges) {
    STILLSLAM_CHECK_LT(e.from, n, "optimize_pose_graph: an edge starts outside the nodes");
    STILLSLAM_CHECK_LT(e.to, n, "optimize_pose_graph: an edge ends outside the nodes");
  }
  for (std::size_t f : fixed_nodes) STILLSLAM_CHECK_LT(f, n, "optimize_pose_graph: a fixed node is outside the nodes");
  for (std::size_t i = 0; i < n; ++i) {
    STILLSLAM_CHECK(T_world_node[i].matrix().allFinite(),
                    "optimize_pose_graph: node " + std::to_string(i) + " has a non-finite pose");
  }
  if (edges.empty() || n == 0) return T_world_node;

  std::vector<Eigen::Quaterniond> q(n);
  std::vector<Eigen::Vector3d> t(n);
  for (std::size_t i = 0; i < n; ++i) {
    q[i] = Eigen::Quaterniond(T_world_node[i].linear()).normalized();
    t[i] = T_world_node[i].translation();
  }

  ceres::Problem problem;
  for (const PoseGraphEdge& e : edges) {
    auto* cost = new ceres::AutoDiffCostFunction<RelativePoseError, 6, 4, 3, 4, 3>(
        new RelativePoseError(e.T_from_to, e.weight));
    problem.AddResidualBlock(cost, nullptr, q[e.from].coeffs().data(), t[e.from].data(), q[e.to].coeffs().data(),
                             t[e.to].data());
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (problem.HasParameterBlock(q[i].coeffs().data())) {
      problem.SetManifold(q[i].coeffs().data(), new ceres::EigenQuaternionManifold);
    }
  }
  bool any_fixed = false;
  for (std::size_t f : fixed_nodes) {
    if (!problem.HasParameterBlock(t[f].data())) continue;
    problem.SetParameterBlockConstant(q[f].coeffs().data());
    problem.SetParameterBlockConstant(t[f].data());
    any_fixed = true;
  }
  if (!any_fixed) {
    // Fix the gauge at the first node that has an edge.
    const std::size_t first = edges.front().from;
    problem.SetParameterBlockConstant(q[first].coeffs().data());
    problem.SetParameterBlockConstant(t[first].data());
  }

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = iterations;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);

  for (std::size_t i = 0; i < n; ++i) {
    T_world_node[i].linear() = q[i].normalized().toRotationMatrix();
    T_world_node[i].translation() = t[i];
  }
  return T_world_node;
}

}  // namespace stillslam
