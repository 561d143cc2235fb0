#pragma once
// A dataset whose frames [first, end) are decoded into memory up front, so a
// run paced like a live camera (--realtime) does not pay image decoding on
// its own cores: a camera driver delivers decoded pixels. Frames outside the
// range are loaded from the source on demand. The memory bound is checked
// from the first frame's size before the rest are decoded, and again while
// decoding (frames may differ); both give an Error naming the fix.
// A frame the source cannot read ends the preloading there; load() of that
// frame throws the same Error, so a run ends where it would without preloading.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "stillslam/io/dataset.h"

namespace stillslam {

class PreloadedDataset final : public Dataset {
 public:
  // Throws Error when frames [first, end) would need more than max_bytes.
  PreloadedDataset(const Dataset& source, std::size_t first, std::size_t end, std::size_t max_bytes);

  std::string kind() const override { return source_.kind(); }
  SensorType sensor() const override { return source_.sensor(); }
  std::size_t size() const override { return source_.size(); }
  double timestamp(std::size_t i) const override { return source_.timestamp(i); }
  // A preloaded frame shares its pixels with the stored copy (no decode, no copy).
  SensorFrame load(std::size_t i) const override;
  std::optional<StereoCalibration> rectified_stereo() const override { return source_.rectified_stereo(); }

  std::size_t bytes() const { return bytes_; }
  std::size_t frames() const { return frames_.size(); }

 private:
  const Dataset& source_;
  std::size_t first_;
  std::vector<SensorFrame> frames_;
  std::optional<std::string> error_;  // why frame first_ + frames_.size() could not be read
  std::size_t bytes_ = 0;
};

}  // namespace stillslam
