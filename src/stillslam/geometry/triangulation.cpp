#include "stillslam/geometry/triangulation.h"

#include <Eigen/SVD>
#include <cmath>

namespace stillslam {

std::optional<Eigen::Vector3d> triangulate(const Eigen::Vector3d& ray1, const Eigen::Isometry3d& T_cam1_world,
                                           const Eigen::Vector3d& ray2, const Eigen::Isometry3d& T_cam2_world,
                                           const TriangulationOptions& options) {
  // Parallax from the rays rotated into the world frame.
  const Eigen::Vector3d d1 = (T_cam1_world.linear().transpose() * ray1).normalized();
  const Eigen::Vector3d d2 = (T_cam2_world.linear().transpose() * ray2).normalized();
  if (d1.dot(d2) >= options.max_cos_parallax) return std::nullopt;

  // Each view gives two rows (x P3 - z P1, y P3 - z P2) with the ray in
  // homogeneous form, so any positive scaling of the ray is allowed.
  const Eigen::Matrix<double, 3, 4> P1 = T_cam1_world.matrix().topRows<3>();
  const Eigen::Matrix<double, 3, 4> P2 = T_cam2_world.matrix().topRows<3>();
  Eigen::Matrix4d A;
  A.row(0) = ray1.x() * P1.row(2) - ray1.z() * P1.row(0);
  A.row(1) = ray1.y() * P1.row(2) - ray1.z() * P1.row(1);
  A.row(2) = ray2.x() * P2.row(2) - ray2.z() * P2.row(0);
  A.row(3) = ray2.y() * P2.row(2) - ray2.z() * P2.row(1);
  // Row scaling does not change the solution but balances conditioning.
  for (int r = 0; r < 4; ++r) {
    const double n = A.row(r).norm();
    if (n > 0) A.row(r) /= n;
  }
  const Eigen::JacobiSVD<Eigen::Matrix4d> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d X = svd.matrixV().col(3);
  if (std::abs(X.w()) < 1e-12) return std::nullopt;
  const Eigen::Vector3d p = X.head<3>() / X.w();
  if ((T_cam1_world * p).z() <= options.min_depth) return std::nullopt;
  if ((T_cam2_world * p).z() <= options.min_depth) return std::nullopt;
  return p;
}

double cos_parallax(const Eigen::Vector3d& point_world, const Eigen::Isometry3d& T_cam1_world,
                    const Eigen::Isometry3d& T_cam2_world) {
  const Eigen::Vector3d c1 = T_cam1_world.inverse().translation();
  const Eigen::Vector3d c2 = T_cam2_world.inverse().translation();
  return (point_world - c1).normalized().dot((point_world - c2).normalized());
}

std::optional<double> depth_from_disparity(double bf, double u_left, double u_right) {
  const double disparity = u_left - u_right;
  if (!(disparity > 0) || !(bf > 0)) return std::nullopt;
  return bf / disparity;
}

}  // namespace stillslam
