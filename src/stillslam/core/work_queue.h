#pragma once
// The one queue type between pipeline stages: FIFO, optionally bounded
// (push blocks while full), stoppable (stop() wakes every waiter; pop() then
// hands out what is left and returns nullopt once empty), and usable without
// a consumer thread (try_pop() drains it synchronously, for deterministic
// runs).
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>

namespace stillslam {

template <class T>
class WorkQueue {
 public:
  // capacity 0: unbounded.
  explicit WorkQueue(std::size_t capacity = 0) : capacity_(capacity) {}
  WorkQueue(const WorkQueue&) = delete;
  WorkQueue& operator=(const WorkQueue&) = delete;

  // Appends `item`, waiting while the queue is full. false (item dropped)
  // when the queue is stopped.
  bool push(T item) {
    std::unique_lock lock(mutex_);
    not_full_.wait(lock, [&] { return stopped_ || capacity_ == 0 || items_.size() < capacity_; });
    if (stopped_) return false;
    items_.push_back(std::move(item));
    not_empty_.notify_one();
    return true;
  }

  // Waits for an item; nullopt once the queue is stopped and empty.
  std::optional<T> pop() {
    std::unique_lock lock(mutex_);
    not_empty_.wait(lock, [&] { return stopped_ || !items_.empty(); });
    return take_front(lock);
  }

  // The front item if there is one, without waiting.
  std::optional<T> try_pop() {
    std::unique_lock lock(mutex_);
    return take_front(lock);
  }

  // Every item not yet popped, in order; the queue is left empty.
  std::deque<T> take_all() {
    std::lock_guard lock(mutex_);
    std::deque<T> out;
    out.swap(items_);
    not_full_.notify_all();
    return out;
  }

  // Later pushes fail; waiting pushers and poppers wake up. Idempotent.
  void stop() {
    std::lock_guard lock(mutex_);
    stopped_ = true;
    not_empty_.notify_all();
    not_full_.notify_all();
  }

  bool stopped() const {
    std::lock_guard lock(mutex_);
    return stopped_;
  }
  std::size_t size() const {
    std::lock_guard lock(mutex_);
    return items_.size();
  }
  bool empty() const { return size() == 0; }
  std::size_t capacity() const { return capacity_; }

 private:
  std::optional<T> take_front(std::unique_lock<std::mutex>&) {
    if (items_.empty()) return std::nullopt;
    std::optional<T> out(std::move(items_.front()));
    items_.pop_front();
    not_full_.notify_one();
    return out;
  }

  const std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable not_empty_;
  std::condition_variable not_full_;
  std::deque<T> items_;
  bool stopped_ = false;
};

}  // namespace stillslam
