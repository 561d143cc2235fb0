#pragma once
#include <vector>

namespace stillslam {

// Per left keypoint: u_right (level-0 pixels of the right image, < 0 if none)
// and depth (metres, < 0 if none).
struct StereoMatches {
  std::vector<float> u_right, depth;
  int num_matches = 0;
};

}  // namespace stillslam
