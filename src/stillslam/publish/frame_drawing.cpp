#include "stillslam/publish/frame_drawing.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "stillslam/core/option_check.h"

namespace stillslam {
namespace {

void draw_mask_outline(cv::Mat& canvas, const cv::Mat1b& mask, const cv::Scalar& color) {
  if (mask.empty() || mask.size() != canvas.size()) return;
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  cv::drawContours(canvas, contours, -1, color, 1, cv::LINE_8);
}

void draw_instances(cv::Mat& canvas, const std::vector<FrameSnapshot::Instance>& instances,
                    const FrameDrawingOptions& options) {
  for (const FrameSnapshot::Instance& instance : instances) {
    const cv::Scalar& color = instance.dynamic ? options.mask : options.static_instance;
    if (instance.outline.size() >= 2) {
      cv::polylines(canvas, std::vector<std::vector<cv::Point>>{instance.outline}, true, color,
                    instance.dynamic ? 2 : 1, cv::LINE_8);
    } else {
      cv::rectangle(canvas, instance.box, color, 1, cv::LINE_8);
    }
    char label[96];
    std::snprintf(label, sizeof(label), "%s %.2f", instance.class_name.c_str(), instance.score);
    const cv::Point at(std::max(0, instance.box.x), std::max(12, instance.box.y - 3));
    cv::putText(canvas, label, at, cv::FONT_HERSHEY_SIMPLEX, 0.4, color, 1, cv::LINE_AA);
  }
}

void draw_state_line(cv::Mat& canvas, const FrameSnapshot& frame, std::size_t kept, std::size_t tracked) {
  char text[256];
  std::snprintf(text, sizeof(text), "#%zu %s | kept %zu, tracked %zu, removed %zu | mask %.1f%%", frame.index,
                frame.state.c_str(), kept, tracked, frame.removed_keypoints.size(), 100.0 * frame.mask_coverage);
  const double scale = canvas.cols >= 640 ? 0.5 : 0.35;
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  cv::rectangle(canvas, cv::Rect(0, 0, std::min(canvas.cols, size.width + 8), size.height + baseline + 6),
                cv::Scalar(0, 0, 0), cv::FILLED);
  cv::putText(canvas, text, cv::Point(4, size.height + 3), cv::FONT_HERSHEY_SIMPLEX, scale,
              cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
}

}  // namespace

void FrameDrawingOptions::check() const {
  using namespace option_check;
  in_range("FrameDrawingOptions.feature_radius", feature_radius, 1, 50);
}

cv::Mat draw_frame(const FrameSnapshot& frame, const FrameDrawingOptions& options) {
  if (frame.image.empty()) return {};
  cv::Mat canvas;
  if (frame.image.channels() == 1) {
    cv::cvtColor(frame.image, canvas, cv::COLOR_GRAY2BGR);
  } else if (frame.image.channels() == 4) {
    cv::cvtColor(frame.image, canvas, cv::COLOR_BGRA2BGR);
  } else {
    canvas = frame.image.clone();
  }
  if (canvas.depth() != CV_8U) canvas.convertTo(canvas, CV_8U);
  // Masks first, features over them, text last.
  draw_mask_outline(canvas, frame.dynamic_mask, options.mask);
  draw_instances(canvas, frame.instances, options);
  const int r = options.feature_radius;
  for (const cv::Point2f& p : frame.removed_keypoints) {
    cv::drawMarker(canvas, p, options.removed, cv::MARKER_CROSS, 2 * r + 1, 1, cv::LINE_8);
  }
  std::size_t tracked = 0;
  for (std::size_t i = 0; i < frame.keypoints.size(); ++i) {
    const bool is_tracked = i < frame.tracked.size() && frame.tracked[i];
    tracked += is_tracked ? 1 : 0;
    cv::circle(canvas, frame.keypoints[i], r, is_tracked ? options.tracked : options.untracked, 1, cv::LINE_8);
  }
  if (options.text) draw_state_line(canvas, frame, frame.keypoints.size(), tracked);
  return canvas;
}

}  // namespace stillslam
