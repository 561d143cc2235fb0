#pragma once
// A slot holding the newest immutable snapshot of something, for any number
// of readers: the writer publishes a shared_ptr<const T>, readers copy the
// pointer (never the object, never under the writer's locks) and can wait for
// a version newer than the one they have.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>

namespace stillslam {

template <class T>
class LatestValue {
 public:
  struct Read {
    std::shared_ptr<const T> value;  // null before the first publish
    std::uint64_t version = 0;       // 0 before the first publish, then 1, 2, ...
  };

  void publish(std::shared_ptr<const T> value) {
    {
      std::lock_guard lock(mutex_);
      value_ = std::move(value);
      ++version_;
    }
    changed_.notify_all();
  }

  Read read() const {
    std::lock_guard lock(mutex_);
    return {value_, version_};
  }

  // Waits until a version newer than `seen` is published, or `timeout`
  // passes; returns what is there then.
  Read wait_newer(std::uint64_t seen, std::chrono::milliseconds timeout) const {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, timeout, [&] { return version_ > seen; });
    return {value_, version_};
  }

 private:
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::shared_ptr<const T> value_;
  std::uint64_t version_ = 0;
};

}  // namespace stillslam
