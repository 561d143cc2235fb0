#include "stillslam/io/preloaded_dataset.h"

#include <algorithm>

#include "stillslam/core/error.h"

namespace stillslam {
namespace {

std::size_t mat_bytes(const cv::Mat& m) { return m.empty() ? 0 : m.total() * m.elemSize(); }

std::string megabytes(std::size_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MB"; }

Error too_big(std::size_t frames, std::size_t bytes, std::size_t max_bytes) {
  return Error("preloading " + std::to_string(frames) + " frames needs about " + megabytes(bytes) +
               ", more than the limit of " + megabytes(max_bytes) +
               ": raise --preload-limit-mb, preload fewer frames (--max-frames), or run without --preload");
}

// Bytes of pixel data a frame holds (colour, gray, right, depth).
std::size_t frame_bytes(const SensorFrame& frame) {
  return mat_bytes(frame.color) + mat_bytes(frame.gray) + mat_bytes(frame.right) + mat_bytes(frame.depth);
}

}  // namespace

PreloadedDataset::PreloadedDataset(const Dataset& source, std::size_t first, std::size_t end, std::size_t max_bytes)
    : source_(source), first_(std::min(first, source.size())) {
  end = std::clamp(end, first_, source.size());
  const std::size_t count = end - first_;
  frames_.reserve(count);
  for (std::size_t i = first_; i < end; ++i) {
    SensorFrame frame;
    try {
      frame = source_.load(i);
    } catch (const Error& e) {
      error_ = e.what();
      break;
    }
    bytes_ += frame_bytes(frame);
    // The first frame's size times the count refuses before decoding the rest.
    const std::size_t expected = i == first_ ? bytes_ * count : bytes_;
    if (expected > max_bytes) throw too_big(count, expected, max_bytes);
    frames_.push_back(std::move(frame));
  }
}

SensorFrame PreloadedDataset::load(std::size_t i) const {
  if (i >= first_ && i - first_ < frames_.size()) return frames_[i - first_];
  if (error_ && i == first_ + frames_.size()) throw Error(*error_);
  return source_.load(i);
}

}  // namespace stillslam
