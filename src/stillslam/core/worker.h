#pragma once
// A pipeline stage that owns its thread: items submitted to it go through a
// WorkQueue and are handled one at a time, in order, by `handler`.
//
// Threaded mode: the worker thread handles them as they come. Synchronous mode
// (deterministic runs, tests): submit() only queues, and the owner handles
// everything queued by calling run_pending() at a point of its choosing, on
// its own thread; no thread is started.
//
// Threaded mode can run a hook on the new thread before the first item
// (e.g. to lower the thread's priority, core/thread_priority.h).
//
// Every worker can be paused (the item in progress finishes, the next one
// waits), stopped (what is queued is still handled, then the thread is
// joined) or cancelled (what is queued is handed back unhandled).
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>

#include "stillslam/core/work_queue.h"

namespace stillslam {

enum class WorkerMode { Threaded, Synchronous };

template <class T>
class Worker {
 public:
  using Handler = std::function<void(T&)>;

  // capacity 0: unbounded queue (submit never waits). on_thread_start:
  // threaded mode, called first on the worker thread (never in synchronous mode).
  Worker(WorkerMode mode, Handler handler, std::size_t capacity = 0, std::function<void()> on_thread_start = {})
      : mode_(mode), handler_(std::move(handler)), on_thread_start_(std::move(on_thread_start)), queue_(capacity) {
    if (mode_ == WorkerMode::Threaded) thread_ = std::thread([this] { run(); });
  }
  ~Worker() { stop(); }
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;

  // Queues an item (waits while a bounded queue is full). false once stopped.
  bool submit(T item) {
    {
      std::lock_guard lock(state_mutex_);
      ++in_flight_;
    }
    if (queue_.push(std::move(item))) return true;
    finished(1);
    return false;
  }

  // Synchronous mode: handles every queued item now, on the caller's thread
  // (also items queued by the handler meanwhile). No-op when threaded.
  void run_pending() {
    if (mode_ == WorkerMode::Threaded) return;
    while (std::optional<T> item = queue_.try_pop()) {
      {
        std::lock_guard lock(state_mutex_);
        busy_ = true;
      }
      handle(*item);
    }
  }

  // Returns when nothing is queued or in progress (synchronous mode: handles
  // it first). Must not be called while paused with items queued.
  void wait_idle() {
    run_pending();
    std::unique_lock lock(state_mutex_);
    state_changed_.wait(lock, [&] { return in_flight_ == 0; });
  }

  // The item in progress finishes; the next one waits until resume() (or a
  // stop). Returns once no item is in progress. No-op in synchronous mode,
  // where nothing runs unless the owner runs it.
  void pause() {
    if (mode_ != WorkerMode::Threaded) return;
    std::unique_lock lock(state_mutex_);
    paused_ = true;
    state_changed_.wait(lock, [&] { return !busy_; });
  }
  void resume() {
    {
      std::lock_guard lock(state_mutex_);
      paused_ = false;
    }
    state_changed_.notify_all();
  }

  // Handles what is queued (also when paused), then joins the thread. Later
  // submits fail. Idempotent.
  void stop() {
    {
      std::lock_guard lock(state_mutex_);
      stopping_ = true;
    }
    state_changed_.notify_all();
    queue_.stop();
    if (thread_.joinable()) thread_.join();
    run_pending();
  }

  // Stops without handling what is queued: the item in progress finishes,
  // the others are returned in order. Later submits fail.
  std::deque<T> cancel() {
    queue_.stop();
    std::deque<T> left = queue_.take_all();
    finished(left.size());
    {
      std::lock_guard lock(state_mutex_);
      stopping_ = true;
    }
    state_changed_.notify_all();
    if (thread_.joinable()) thread_.join();
    return left;
  }

  bool threaded() const { return mode_ == WorkerMode::Threaded; }
  // pause() was called and resume() not yet.
  bool paused() const {
    std::lock_guard lock(state_mutex_);
    return paused_;
  }
  // Submitted and not started: also an item the thread has taken from the
  // queue but holds while paused, so a paused worker reports what waits.
  std::size_t queued() const {
    std::lock_guard lock(state_mutex_);
    return in_flight_ - (busy_ ? 1 : 0);
  }
  // Nothing queued and nothing in progress.
  bool idle() const {
    std::lock_guard lock(state_mutex_);
    return in_flight_ == 0;
  }

 private:
  void run() {
    if (on_thread_start_) on_thread_start_();
    while (std::optional<T> item = queue_.pop()) {
      {
        // busy_ is set under the same lock as the pause check, so pause()
        // never returns while an item is about to start.
        std::unique_lock lock(state_mutex_);
        state_changed_.wait(lock, [&] { return !paused_ || stopping_; });
        busy_ = true;
      }
      handle(*item);
    }
  }

  void handle(T& item) {
    handler_(item);
    {
      std::lock_guard lock(state_mutex_);
      busy_ = false;
    }
    finished(1);
  }

  void finished(std::size_t n) {
    {
      std::lock_guard lock(state_mutex_);
      in_flight_ -= n;
    }
    state_changed_.notify_all();
  }

  const WorkerMode mode_;
  Handler handler_;
  std::function<void()> on_thread_start_;
  WorkQueue<T> queue_;
  mutable std::mutex state_mutex_;
  std::condition_variable state_changed_;
  std::size_t in_flight_ = 0;  // submitted and not yet handled (queued + in progress)
  bool busy_ = false;          // an item is in progress
  bool paused_ = false;
  bool stopping_ = false;
  std::thread thread_;  // last: starts after the members above exist
};

}  // namespace stillslam
