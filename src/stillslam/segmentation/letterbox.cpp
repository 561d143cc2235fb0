#include "stillslam/segmentation/letterbox.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace stillslam {

Letterbox Letterbox::fit(cv::Size frame, cv::Size input) {
  Letterbox lb;
  lb.frame = frame;
  lb.input = input;
  lb.scale = std::min(static_cast<double>(input.width) / frame.width, static_cast<double>(input.height) / frame.height);
  lb.resized = cv::Size(static_cast<int>(std::lround(frame.width * lb.scale)),
                        static_cast<int>(std::lround(frame.height * lb.scale)));
  lb.resized.width = std::clamp(lb.resized.width, 1, input.width);  // >= 1 even for a 1x5000 strip
  lb.resized.height = std::clamp(lb.resized.height, 1, input.height);
  // Same rounding as Ultralytics (round(d/2 - 0.1)) so boxes match its reference outputs.
  lb.pad_x = static_cast<int>(std::lround((input.width - lb.resized.width) / 2.0 - 0.1));
  lb.pad_y = static_cast<int>(std::lround((input.height - lb.resized.height) / 2.0 - 0.1));
  return lb;
}

cv::Mat Letterbox::apply(const cv::Mat& frame_image) const {
  cv::Mat out(input, frame_image.type(), cv::Scalar::all(114));
  cv::Mat roi = out(cv::Rect(cv::Point(pad_x, pad_y), resized));
  if (resized == frame_image.size())
    frame_image.copyTo(roi);
  else
    cv::resize(frame_image, roi, resized, 0, 0, cv::INTER_LINEAR);
  return out;
}

cv::Point2f Letterbox::to_frame(cv::Point2f p) const {
  return {static_cast<float>((p.x - pad_x) / scale), static_cast<float>((p.y - pad_y) / scale)};
}

}  // namespace stillslam
