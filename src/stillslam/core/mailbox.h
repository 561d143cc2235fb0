#pragma once
// Latest-value hand-over between two stages where stale work should be
// skipped: put() replaces a value nobody has taken yet (counted as skipped),
// take() hands the newest one to a single consumer and empties the box.
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <optional>

namespace stillslam {

template <class T>
class Mailbox {
 public:
  Mailbox() = default;
  Mailbox(const Mailbox&) = delete;
  Mailbox& operator=(const Mailbox&) = delete;

  // Leaves `value` for the consumer; true when it replaced an untaken one.
  // Ignored (false) once stopped.
  bool put(T value) {
    std::lock_guard lock(mutex_);
    if (stopped_) return false;
    const bool replaced = value_.has_value();
    if (replaced) ++skipped_;
    value_.emplace(std::move(value));
    changed_.notify_one();
    return replaced;
  }

  // Waits for a value; nullopt once stopped (an untaken value is dropped).
  std::optional<T> take() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return stopped_ || value_.has_value(); });
    if (stopped_) return std::nullopt;
    return release();
  }

  // The value if there is one, without waiting.
  std::optional<T> try_take() {
    std::lock_guard lock(mutex_);
    return release();
  }

  void stop() {
    std::lock_guard lock(mutex_);
    stopped_ = true;
    value_.reset();
    changed_.notify_all();
  }

  // Values replaced before anyone took them.
  std::size_t skipped() const {
    std::lock_guard lock(mutex_);
    return skipped_;
  }

 private:
  std::optional<T> release() {
    std::optional<T> out;
    out.swap(value_);
    return out;
  }

  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<T> value_;
  std::size_t skipped_ = 0;
  bool stopped_ = false;
};

}  // namespace stillslam
