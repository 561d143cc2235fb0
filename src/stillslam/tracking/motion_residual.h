#pragma once
// How far a feature seen in an earlier frame lies from where the camera motion
// alone puts it now. Static points give residuals at the level of the
// keypoint and pose noise; points on things that moved in between give more,
// in proportion to how far they moved. Pixel units, in the current frame.
#include <Eigen/Geometry>

#include "stillslam/geometry/pinhole_camera.h"

namespace stillslam {

// With the feature's depth in the earlier frame: the back-projected point,
// moved by T_cur_prev and projected, against where it was found now.
// Infinite when the point falls behind the current camera.
double reprojection_residual(const PinholeCamera& camera, const Eigen::Isometry3d& T_cur_prev,
                             const Eigen::Vector2d& prev_pixel, double prev_depth, const Eigen::Vector2d& cur_pixel);

// Without depth: distance of cur_pixel from the epipolar line of prev_pixel.
// Blind to motion along that line (a weaker test: use depth when there is).
// Zero when the camera did not translate (no epipolar geometry: the caller
// should then compare with the rotation-only prediction instead).
double epipolar_residual(const PinholeCamera& camera, const Eigen::Isometry3d& T_cur_prev,
                         const Eigen::Vector2d& prev_pixel, const Eigen::Vector2d& cur_pixel);

}  // namespace stillslam
