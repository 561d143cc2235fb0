#pragma once
// Keypoint orientation by the intensity centroid (Rosin; used by ORB): the
// angle of the vector from the keypoint to the centroid of intensities in a
// disc of radius 15 around it.
#include <opencv2/core.hpp>
#include <vector>

namespace stillslam {

inline constexpr int kOrientationRadius = 15;

// Sets keypoint.angle (degrees, [0, 360), image axes: x right, y down) for
// keypoints at integer positions of `image` (CV_8UC1), each at least
// kOrientationRadius pixels from the border.
void compute_orientations(const cv::Mat& image, std::vector<cv::KeyPoint>& keypoints);

// Disc half-widths: row v of the disc spans u in [-half_width[|v|], half_width[|v|]].
// Defined by u^2 + v^2 <= r^2, so the disc is exactly symmetric under 90 degree
// rotations.
std::vector<int> disc_half_widths(int radius);

}  // namespace stillslam
