#pragma once
// builtin_interfaces/Time (the header stamp) to and from stillslam's seconds.
// Pairing and matching use whole nanoseconds, so equal stamps compare equal.
#include <cmath>
#include <cstdint>

#include "builtin_interfaces/msg/Time.h"

namespace stillslam::ros2 {

inline std::int64_t stamp_nanoseconds(const builtin_interfaces_msg_dds__Time_& t) {
  return static_cast<std::int64_t>(t.sec) * 1000000000LL + t.nanosec;
}

inline builtin_interfaces_msg_dds__Time_ stamp_from_nanoseconds(std::int64_t ns) {
  std::int64_t sec = ns / 1000000000LL;
  std::int64_t rest = ns % 1000000000LL;
  if (rest < 0) {
    rest += 1000000000LL;
    --sec;
  }
  return {static_cast<std::int32_t>(sec), static_cast<std::uint32_t>(rest)};
}

inline std::int64_t nanoseconds_from_seconds(double t) { return std::llround(t * 1e9); }
inline double seconds_from_nanoseconds(std::int64_t ns) {
  // Whole seconds and the rest apart: one division would lose the last digits.
  return static_cast<double>(ns / 1000000000LL) + static_cast<double>(ns % 1000000000LL) * 1e-9;
}

}  // namespace stillslam::ros2
