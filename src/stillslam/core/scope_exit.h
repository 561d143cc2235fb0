#pragma once
// Calls a function when the scope ends, however it is left (return or
// exception): the run loops' "viewer, let go of this System" hook.
#include <functional>
#include <utility>

namespace stillslam {

class ScopeExit {
 public:
  explicit ScopeExit(std::function<void()> f) : f_(std::move(f)) {}
  ScopeExit(const ScopeExit&) = delete;
  ScopeExit& operator=(const ScopeExit&) = delete;
  ~ScopeExit() {
    if (f_) f_();
  }

 private:
  std::function<void()> f_;
};

}  // namespace stillslam
