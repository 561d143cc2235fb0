#include "stillslam/tracking/keypoint_pixels.h"

namespace stillslam {

std::vector<cv::Point2f> keypoint_pixels(const Frame& frame) {
  std::vector<cv::Point2f> out;
  out.reserve(frame.size());
  for (const cv::KeyPoint& k : frame.keypoints_raw()) out.push_back(k.pt);
  return out;
}

}  // namespace stillslam
