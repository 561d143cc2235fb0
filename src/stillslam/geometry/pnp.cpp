#include "stillslam/geometry/pnp.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <random>
#include <string>

#include "stillslam/core/check.h"

namespace stillslam {
namespace {

Eigen::Isometry3d from_rvec_tvec(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Mat R;
  cv::Rodrigues(rvec, R);
  Eigen::Matrix3d Re;
  cv::cv2eigen(R, Re);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Re;
  T.translation() = Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2));
  return T;
}

// Inliers by reprojection error; points behind the camera are outliers.
int classify_pnp(const PinholeCamera& camera, const Eigen::Isometry3d& T_cam_world,
                 const std::vector<Eigen::Vector3d>& points_world, const std::vector<Eigen::Vector2d>& pixels,
                 double max_error_px, std::vector<bool>& inlier) {
  const double max2 = max_error_px * max_error_px;
  inlier.assign(points_world.size(), false);
  int n = 0;
  for (std::size_t i = 0; i < points_world.size(); ++i) {
    const Eigen::Vector3d pc = T_cam_world * points_world[i];
    if (pc.z() <= 0) continue;
    if ((camera.project(pc) - pixels[i]).squaredNorm() <= max2) {
      inlier[i] = true;
      ++n;
    }
  }
  return n;
}

}  // namespace

PnpResult solve_pnp_ransac(const PinholeCamera& camera, const std::vector<Eigen::Vector3d>& points_world,
                           const std::vector<Eigen::Vector2d>& pixels_undistorted, const PnpRansacOptions& options) {
  STILLSLAM_CHECK_EQ(points_world.size(), pixels_undistorted.size(), "solve_pnp_ransac: pass one pixel per point");
  PnpResult result;
  result.inlier.assign(points_world.size(), false);
  if (points_world.size() < 4) return result;

  std::vector<cv::Point3d> object(points_world.size());
  std::vector<cv::Point2d> image(points_world.size());
  for (std::size_t i = 0; i < points_world.size(); ++i) {
    object[i] = {points_world[i].x(), points_world[i].y(), points_world[i].z()};
    image[i] = {pixels_undistorted[i].x(), pixels_undistorted[i].y()};
  }
  const cv::Mat K = camera.K();
  cv::Mat rvec, tvec;
  std::vector<int> inlier_idx;
  // EPnP minimal sets need 5 points but are robust; AP3P takes 4. OpenCV's
  // RANSAC uses a fixed RNG seed, so results are reproducible.
  const int flag = points_world.size() >= 6 ? cv::SOLVEPNP_EPNP : cv::SOLVEPNP_AP3P;
  bool ok = false;
  try {
    ok = cv::solvePnPRansac(object, image, K, cv::noArray(), rvec, tvec, false, options.max_iterations,
                            static_cast<float>(options.max_reprojection_error_px), options.confidence, inlier_idx,
                            flag);
  } catch (const cv::Exception&) {
    ok = false;  // degenerate configurations make the minimal solvers throw
  }
  if (!ok || static_cast<int>(inlier_idx.size()) < std::max(4, options.min_inliers)) return result;

  Eigen::Isometry3d T = from_rvec_tvec(rvec, tvec);
  std::vector<bool> inlier;
  int n = classify_pnp(camera, T, points_world, pixels_undistorted, options.max_reprojection_error_px, inlier);
  if (options.refine && n >= 4) {
    // Two refine/reclassify passes: the refit can pull in points that the
    // minimal-set model just missed.
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<cv::Point3d> obj_in;
      std::vector<cv::Point2d> img_in;
      for (std::size_t i = 0; i < inlier.size(); ++i) {
        if (!inlier[i]) continue;
        obj_in.push_back(object[i]);
        img_in.push_back(image[i]);
      }
      cv::solvePnPRefineLM(obj_in, img_in, K, cv::noArray(), rvec, tvec);
      const Eigen::Isometry3d T_refined = from_rvec_tvec(rvec, tvec);
      std::vector<bool> inlier_refined;
      const int n_refined = classify_pnp(camera, T_refined, points_world, pixels_undistorted,
                                         options.max_reprojection_error_px, inlier_refined);
      if (n_refined < n) break;
      T = T_refined;
      inlier = std::move(inlier_refined);
      n = n_refined;
    }
  }
  if (n < std::max(4, options.min_inliers)) return result;
  result.success = true;
  result.T_cam_world = T;
  result.inlier = std::move(inlier);
  result.num_inliers = n;
  return result;
}

Sim3 align_umeyama(const std::vector<Eigen::Vector3d>& src, const std::vector<Eigen::Vector3d>& dst,
                   bool with_scale) {
  STILLSLAM_CHECK_EQ(src.size(), dst.size(), "align_umeyama: pass matched pairs");
  STILLSLAM_CHECK_GE(src.size(), 3u, "align_umeyama: needs at least 3 point pairs");
  Eigen::Matrix3Xd S(3, src.size()), D(3, dst.size());
  for (std::size_t i = 0; i < src.size(); ++i) {
    S.col(static_cast<Eigen::Index>(i)) = src[i];
    D.col(static_cast<Eigen::Index>(i)) = dst[i];
  }
  const Eigen::Matrix4d M = Eigen::umeyama(S, D, with_scale);
  const Eigen::Matrix3d sR = M.topLeftCorner<3, 3>();
  const double s = with_scale ? std::cbrt(sR.determinant()) : 1.0;
  return Sim3(s, sR / s, M.topRightCorner<3, 1>());
}

AlignmentResult align_ransac(const std::vector<Eigen::Vector3d>& src, const std::vector<Eigen::Vector3d>& dst,
                             const AlignmentRansacOptions& options) {
  STILLSLAM_CHECK_EQ(src.size(), dst.size(), "align_ransac: pass matched pairs");
  AlignmentResult result;
  const std::size_t n = src.size();
  result.inlier.assign(n, false);
  if (n < 3) return result;

  const double max2 = options.max_error * options.max_error;
  auto classify = [&](const Sim3& S, std::vector<bool>& inlier) {
    inlier.assign(n, false);
    int count = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if ((dst[i] - S * src[i]).squaredNorm() <= max2) {
        inlier[i] = true;
        ++count;
      }
    }
    return count;
  };

  std::mt19937_64 rng(options.seed);
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  int best = -1;
  Sim3 best_model;
  std::vector<bool> inlier;
  int needed = options.max_iterations;
  for (int it = 0; it < needed; ++it) {
    std::size_t a = pick(rng), b = pick(rng), c = pick(rng);
    if (a == b || a == c || b == c) continue;
    // Skip nearly collinear samples: the rotation about their line is free.
    const Eigen::Vector3d e1 = src[b] - src[a], e2 = src[c] - src[a];
    if (e1.cross(e2).norm() < 1e-9 * (e1.squaredNorm() + e2.squaredNorm() + 1e-30)) continue;
    const Sim3 model = align_umeyama({src[a], src[b], src[c]}, {dst[a], dst[b], dst[c]}, options.with_scale);
    const int count = classify(model, inlier);
    if (count > best) {
      best = count;
      best_model = model;
      // Adaptive iteration count for the requested confidence.
      const double w = static_cast<double>(count) / static_cast<double>(n);
      const double p_fail = 1.0 - w * w * w;
      if (p_fail <= 1e-12) {
        needed = it + 1;
      } else if (p_fail < 1.0) {
        const double k = std::log(1.0 - options.confidence) / std::log(p_fail);
        if (k < options.max_iterations) needed = std::max(it + 1, static_cast<int>(std::ceil(k)));
      }
    }
  }
  if (best < std::max(3, options.min_inliers)) return result;

  // Refit on inliers until the inlier set stops growing.
  Sim3 model = best_model;
  int count = classify(model, inlier);
  for (int pass = 0; pass < 3; ++pass) {
    std::vector<Eigen::Vector3d> s_in, d_in;
    for (std::size_t i = 0; i < n; ++i) {
      if (!inlier[i]) continue;
      s_in.push_back(src[i]);
      d_in.push_back(dst[i]);
    }
    const Sim3 refit = align_umeyama(s_in, d_in, options.with_scale);
    std::vector<bool> refit_inlier;
    const int refit_count = classify(refit, refit_inlier);
    if (refit_count < count) break;
    const bool grew = refit_count > count;
    model = refit;
    inlier = std::move(refit_inlier);
    count = refit_count;
    if (!grew) break;
  }
  if (count < std::max(3, options.min_inliers)) return result;
  result.success = true;
  result.S_dst_src = model;
  result.inlier = std::move(inlier);
  result.num_inliers = count;
  return result;
}

}  // namespace stillslam
