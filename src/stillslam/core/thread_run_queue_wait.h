#pragma once
// How long the calling thread has waited for a core: the time it was ready
// to run but sat on a run queue (Linux: the second field of
// /proc/thread-self/schedstat, nanoseconds). Waiting for a lock, a queue or a
// sleep does not count. On a two-core machine this is the share of a frame's
// wall time lost to the other threads; nullopt where it is not available.
#include <fstream>
#include <optional>

namespace stillslam {

inline std::optional<double> this_thread_run_queue_wait_ms() {
  std::ifstream in("/proc/thread-self/schedstat");
  unsigned long long run_ns = 0, wait_ns = 0;
  if (!(in >> run_ns >> wait_ns)) return std::nullopt;
  return static_cast<double>(wait_ns) * 1e-6;
}

}  // namespace stillslam
