#pragma once
// Absolute pose (PnP) and 3D-3D alignment in RANSAC, for relocalization and
// loop closing. Both are deterministic (fixed seeds).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "stillslam/geometry/pinhole_camera.h"
#include "stillslam/geometry/se3.h"

namespace stillslam {

struct PnpRansacOptions {
  int max_iterations = 300;
  double max_reprojection_error_px = 2.5;
  double confidence = 0.99;
  int min_inliers = 10;
  // Re-estimate on all inliers with Levenberg-Marquardt (cv::solvePnPRefineLM).
  bool refine = true;
};

struct PnpResult {
  bool success = false;
  Eigen::Isometry3d T_cam_world = Eigen::Isometry3d::Identity();
  std::vector<bool> inlier;  // per correspondence
  int num_inliers = 0;
};

// points_world[i] seen at undistorted pixels[i]. Needs >= 4 correspondences
// (returns success = false otherwise).
PnpResult solve_pnp_ransac(const PinholeCamera& camera,
                           const std::vector<Eigen::Vector3d>& points_world,
                           const std::vector<Eigen::Vector2d>& pixels_undistorted,
                           const PnpRansacOptions& options = {});

// Closed-form least-squares alignment (Umeyama): the S_dst_src minimizing
// sum |dst_i - S * src_i|^2; scale fixed to 1 unless with_scale. Needs >= 3
// non-collinear pairs of equal count (throws stillslam::Error on size mismatch).
Sim3 align_umeyama(const std::vector<Eigen::Vector3d>& src, const std::vector<Eigen::Vector3d>& dst,
                   bool with_scale = false);

struct AlignmentRansacOptions {
  int max_iterations = 300;
  // An inlier's residual |dst - S * src| in metres.
  double max_error = 0.05;
  double confidence = 0.995;
  int min_inliers = 6;
  bool with_scale = false;
  std::uint64_t seed = 7;
};

struct AlignmentResult {
  bool success = false;
  Sim3 S_dst_src;
  std::vector<bool> inlier;
  int num_inliers = 0;
};

// 3-point RANSAC around align_umeyama, refit on the final inliers.
AlignmentResult align_ransac(const std::vector<Eigen::Vector3d>& src,
                             const std::vector<Eigen::Vector3d>& dst,
                             const AlignmentRansacOptions& options = {});

}  // namespace stillslam
