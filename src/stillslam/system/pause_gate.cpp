#include "stillslam/system/pause_gate.h"

namespace stillslam {

void PauseGate::pause() {
  std::lock_guard lock(mutex_);
  paused_ = true;
  steps_ = 0;
}

void PauseGate::resume() {
  {
    std::lock_guard lock(mutex_);
    paused_ = false;
    steps_ = 0;
  }
  changed_.notify_all();
}

void PauseGate::step() {
  {
    std::lock_guard lock(mutex_);
    if (paused_) ++steps_;
    paused_ = true;
  }
  changed_.notify_all();
}

bool PauseGate::paused() const {
  std::lock_guard lock(mutex_);
  return paused_;
}

std::uint64_t PauseGate::passed() const {
  std::lock_guard lock(mutex_);
  return passed_;
}

bool PauseGate::wait(const std::atomic<bool>* stop, std::chrono::milliseconds poll) {
  std::unique_lock lock(mutex_);
  for (;;) {
    if (stop != nullptr && stop->load()) return false;
    if (!paused_ || steps_ > 0) break;
    changed_.wait_for(lock, poll);
  }
  if (paused_ && steps_ > 0) --steps_;
  ++passed_;
  return true;
}

}  // namespace stillslam
