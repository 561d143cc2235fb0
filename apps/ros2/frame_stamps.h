#pragma once
// The exact header stamps (nanoseconds) of the frames handed to the System,
// by frame index, so outputs carry the input's stamp to the nanosecond (a
// double of seconds since 1970 holds only ~0.2 us). Bounded: the newest
// kCapacity frames, more than the mailbox and the publish layer can hold
// back.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <utility>

#include "ros_time.h"

namespace stillslam::ros2 {

class FrameStamps {
 public:
  static constexpr std::size_t kCapacity = 64;
  void record(std::size_t index, std::int64_t stamp_ns) {
    std::lock_guard lock(mutex_);
    stamps_.emplace_back(index, stamp_ns);
    if (stamps_.size() > kCapacity) stamps_.pop_front();
  }
  // The recorded stamp of `index`; else `seconds` rounded to nanoseconds.
  std::int64_t stamp_ns(std::size_t index, double seconds) const {
    std::lock_guard lock(mutex_);
    for (auto it = stamps_.rbegin(); it != stamps_.rend(); ++it) {
      if (it->first == index) return it->second;
    }
    return nanoseconds_from_seconds(seconds);
  }

 private:
  mutable std::mutex mutex_;
  std::deque<std::pair<std::size_t, std::int64_t>> stamps_;
};

}  // namespace stillslam::ros2
