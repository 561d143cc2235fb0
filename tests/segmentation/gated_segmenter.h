#pragma once
// A test double for the asynchronous segmentation: reports one "person",
// a 10x10 square at x = frame index, y = 0 (so a result's source frame shows
// in its mask), records the frames it was asked for and, while the gate is
// closed, blocks each call until release() (at most `safety` long, so a
// broken test fails instead of hanging; `timed_out` says it happened).
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <memory>
#include <mutex>
#include <vector>

#include "stillslam/segmentation/segmenter.h"

namespace stillslam::test {

struct Gate {
  std::mutex mutex;
  std::condition_variable changed;
  bool open = true;
  int waiting = 0;  // calls blocked now
  bool timed_out = false;
  std::vector<std::size_t> segmented;  // frame indices, in call order

  void close() {
    std::lock_guard lock(mutex);
    open = false;
  }
  void release() {
    {
      std::lock_guard lock(mutex);
      open = true;
    }
    changed.notify_all();
  }
  // Waits until a call is blocked at the gate.
  void wait_blocked() {
    std::unique_lock lock(mutex);
    changed.wait_for(lock, std::chrono::seconds(20), [&] { return waiting > 0; });
  }
};

class GatedSegmenter final : public Segmenter {
 public:
  explicit GatedSegmenter(std::shared_ptr<Gate> gate) : gate_(std::move(gate)) {}
  std::vector<Detection> segment(const cv::Mat& bgr) override { return segment_frame(bgr, 0); }
  std::vector<Detection> segment_frame(const cv::Mat& bgr, std::size_t frame_index) override {
    {
      std::unique_lock lock(gate_->mutex);
      gate_->segmented.push_back(frame_index);
      ++gate_->waiting;
      gate_->changed.notify_all();
      if (!gate_->changed.wait_for(lock, std::chrono::seconds(20), [&] { return gate_->open; })) {
        gate_->timed_out = true;
      }
      --gate_->waiting;
    }
    Detection d;
    d.class_id = 0;
    d.class_name = "person";
    d.score = 1.f;
    const int x = static_cast<int>(frame_index) % (bgr.cols - 10);
    d.box = cv::Rect2f(static_cast<float>(x), 0, 10, 10);
    d.mask = cv::Mat1b::zeros(bgr.rows, bgr.cols);
    d.mask(cv::Rect(x, 0, 10, 10)).setTo(255);
    return {d};
  }

 private:
  std::shared_ptr<Gate> gate_;
};

// The x of the square in a result's mask: its source frame index.
inline int square_x(const cv::Mat1b& mask) {
  for (int x = 0; x < mask.cols; ++x) {
    if (mask(0, x)) return x;
  }
  return -1;
}

}  // namespace stillslam::test
