#pragma once
// A segmenter with a known answer for system tests: one "person", a 40x40
// square in the top-left corner of every image (a small mask, so the map's
// start is checked with masks, Tracking.initConfirmFrames).
#include <opencv2/core.hpp>

#include <vector>

#include "stillslam/segmentation/segmenter.h"

namespace stillslam::test {

class CornerPerson final : public Segmenter {
 public:
  std::vector<Detection> segment(const cv::Mat& bgr) override {
    Detection d;
    d.class_id = 0;
    d.class_name = "person";
    d.score = 1.f;
    d.box = cv::Rect2f(0, 0, 40, 40);
    d.mask = cv::Mat1b::zeros(bgr.rows, bgr.cols);
    d.mask(cv::Rect(0, 0, 40, 40)).setTo(255);
    return {d};
  }
};

}  // namespace stillslam::test
