#pragma once
// Structural checks of the records a map file holds (map_file.cpp runs them
// after the checksum, which a damaged or hand-edited file can still match).
// Each returns what is wrong with a record, or nothing when it is sane.
#include <Eigen/Core>
#include <opencv2/core/types.hpp>
#include <optional>
#include <string>

namespace stillslam::map_file_checks {

using Problem = std::optional<std::string>;

// A 3x4 [R|t] (row-major T_cam_world): finite, R a rotation.
Problem pose(const Eigen::Matrix<double, 3, 4>& T);
// A keypoint of a pyramid with `levels` levels: finite coordinates, size,
// angle and response, octave in range.
Problem keypoint(const cv::KeyPoint& kp, int levels);
// Right coordinate and depth of a keypoint: finite (negative: unknown).
Problem stereo(float u_right, float depth);
// A map point's geometry and statistics: finite position, unit (or zero)
// normal, 0 <= min <= max distance, non-negative visible/found counts.
Problem point(const Eigen::Vector3d& position, const Eigen::Vector3d& normal, double min_distance,
              double max_distance, int visible, int found);

}  // namespace stillslam::map_file_checks
