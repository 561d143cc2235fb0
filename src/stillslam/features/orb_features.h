#pragma once
#include <opencv2/core.hpp>
#include <vector>

namespace stillslam {

// Keypoints and their descriptors from one image.
// keypoints: level-0 pixel coordinates, octave = pyramid level, angle in
// degrees [0, 360) (intensity-centroid direction, y axis pointing down),
// size = patch diameter at that level, response = FAST score.
// descriptors: N x 32 CV_8U rows (256-bit steered BRIEF), row i for keypoint i.
struct OrbFeatures {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;

  std::size_t size() const { return keypoints.size(); }
  bool empty() const { return keypoints.empty(); }
};

}  // namespace stillslam
