#pragma once
#include <opencv2/core.hpp>

namespace stillslam {

// Fits a frame into the network input keeping the aspect ratio, padding with
// gray 114 (Ultralytics LetterBox, centered, bilinear resize).
struct Letterbox {
  double scale = 1.0;   // input pixels per frame pixel
  int pad_x = 0;        // left padding, input pixels
  int pad_y = 0;        // top padding, input pixels
  cv::Size resized;     // size of the frame inside the input
  cv::Size frame;       // original frame size
  cv::Size input;       // network input size

  static Letterbox fit(cv::Size frame, cv::Size input);
  cv::Mat apply(const cv::Mat& frame_image) const;  // -> input-size image
  // Input pixel coordinates -> frame pixel coordinates (not clipped).
  cv::Point2f to_frame(cv::Point2f input_point) const;
};

}  // namespace stillslam
