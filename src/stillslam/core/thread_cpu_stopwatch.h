#pragma once
// CPU time consumed by the calling thread (CLOCK_THREAD_CPUTIME_ID). On a
// shared, oversubscribed machine wall-clock times mostly measure waiting;
// thread CPU time is what the work costs on a core of its own.
#include <ctime>

namespace stillslam {

class ThreadCpuStopwatch {
 public:
  ThreadCpuStopwatch() : start_(now_ms()) {}
  double elapsed_ms() const { return now_ms() - start_; }

 private:
  static double now_ms() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
  }
  double start_;
};

}  // namespace stillslam
