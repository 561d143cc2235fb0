#pragma once
// Turns SIGINT, SIGTERM, SIGHUP (closed terminal or ssh session) and SIGQUIT
// into a stop request for `run`. The signals are blocked in every thread
// (threads started later inherit the mask) and taken by one watcher thread
// with sigtimedwait, so no signal handler or global flag is needed and no
// signal can cut an output file while it is written. Built first thing in the
// command, so a signal during settings, model or dataset loading stops the
// run before its first frame instead of killing the process. Signals the
// caller ignores (nohup, a shell's background job) stay ignored.
#include <signal.h>

#include <atomic>
#include <string>
#include <thread>

namespace stillslam::apps {

class SignalWatcher {
 public:
  SignalWatcher();
  // Stops the watcher thread. The signals stay blocked: the process is about
  // to exit, and a late signal must not kill it between its last outputs and
  // its exit code.
  ~SignalWatcher();
  SignalWatcher(const SignalWatcher&) = delete;
  SignalWatcher& operator=(const SignalWatcher&) = delete;

  const std::atomic<bool>& stop() const { return stop_; }
  int signal() const { return signal_; }  // the first signal taken, 0 while none

 private:
  void take(int signal);  // a sigtimedwait result: a signal number, or <= 0 for none

  sigset_t set_{};
  std::atomic<bool> stop_{false}, done_{false};
  std::atomic<int> signal_{0};
  std::thread thread_;
};

// "SIGINT", "SIGTERM", "SIGHUP", "SIGQUIT"; "signal N" for others.
std::string signal_name(int signal);

}  // namespace stillslam::apps
