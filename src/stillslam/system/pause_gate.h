#pragma once
// Lets another thread (the viewer's pause / step / resume buttons) hold the
// run loop between frames. The run loop calls wait() before each frame; it
// returns at once while running, blocks while paused, and lets exactly one
// frame through per step(). Thread safe.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>

namespace stillslam {

class PauseGate {
 public:
  void pause();
  void resume();
  // Paused: lets one more frame through, then holds again. Running: pauses
  // (the frame in progress finishes).
  void step();
  bool paused() const;
  // Frames that went through the gate so far.
  std::uint64_t passed() const;

  // Blocks while paused (and no step is pending); returns false when `stop`
  // is set meanwhile (checked every `poll`: a signal handler cannot notify).
  bool wait(const std::atomic<bool>* stop,
            std::chrono::milliseconds poll = std::chrono::milliseconds(100));

 private:
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  bool paused_ = false;
  int steps_ = 0;  // frames allowed through while paused
  std::uint64_t passed_ = 0;
};

}  // namespace stillslam
