#pragma once
#include <opencv2/core.hpp>

#include <string>

namespace stillslam {

// One instance found by a Segmenter, in the pixels of the frame that was segmented.
struct Detection {
  int class_id = -1;
  std::string class_name;
  float score = 0.0f;
  cv::Rect2f box;  // frame pixels; x, y = top-left corner
  cv::Mat1b mask;  // frame-size, 255 inside the instance; empty when masks were restricted to other classes
};

}  // namespace stillslam
