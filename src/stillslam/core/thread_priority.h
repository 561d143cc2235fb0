#pragma once
// A pipeline thread's scheduling priority relative to the others. On Linux
// every thread has a nice value of its own: setpriority(PRIO_PROCESS, tid)
// changes the calling thread's only (a new thread starts with its creator's).
// Raising it (lowering the priority) needs no privileges. On two cores the
// tracking thread must not wait for a core behind the segmenter: a higher
// nice value makes the scheduler run the tracker first when both want a core.
// Elsewhere these report "not supported" and change nothing.
#include <cerrno>
#include <cstring>
#include <optional>
#include <string>

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace stillslam {

// The nice values a thread can have (Linux).
inline constexpr int kMaxNice = 19;

// The calling thread's nice value; nullopt where not supported.
inline std::optional<int> this_thread_nice() {
#if defined(__linux__)
  const auto tid = static_cast<id_t>(syscall(SYS_gettid));
  errno = 0;
  const int nice = getpriority(PRIO_PROCESS, tid);  // -1 is a valid value: errno tells
  if (nice == -1 && errno != 0) return std::nullopt;
  return nice;
#else
  return std::nullopt;
#endif
}

// Raises the calling thread's nice value by `increment` (> 0; kMaxNice at
// most), leaving the process's other threads as they are. Returns an empty
// string when done (or for increment <= 0), else why not.
inline std::string lower_this_thread_priority(int increment) {
  if (increment <= 0) return {};
#if defined(__linux__)
  const std::optional<int> now = this_thread_nice();
  if (!now) return std::string("cannot read the thread's nice value: ") + std::strerror(errno);
  const int target = *now + increment < kMaxNice ? *now + increment : kMaxNice;
  const auto tid = static_cast<id_t>(syscall(SYS_gettid));
  if (setpriority(PRIO_PROCESS, tid, target) != 0) {
    return "setpriority(" + std::to_string(target) + ") failed: " + std::strerror(errno);
  }
  return {};
#else
  return "per-thread priorities are supported on Linux only";
#endif
}

}  // namespace stillslam
