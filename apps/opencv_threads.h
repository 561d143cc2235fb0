#pragma once
// OpenCV has one thread pool for the whole process, shared by the YOLO network
// (DNN) and ORB extraction's parallel_for_. No library call sizes it: each
// command sizes it once, before any work, so every run of a process (bench
// runs "off" and "on" one after the other) computes with the same setting.
#include <opencv2/core.hpp>
#include <spdlog/spdlog.h>

namespace stillslam::apps {

// n > 0: that many threads; 0: OpenCV's default (all cores).
inline void set_opencv_threads(int n) {
  if (n > 0) cv::setNumThreads(n);
  spdlog::debug("OpenCV thread pool: {} threads", cv::getNumThreads());
}

}  // namespace stillslam::apps
