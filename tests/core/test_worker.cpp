#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <thread>
#include <vector>

#include "stillslam/core/latest_value.h"
#include "stillslam/core/mailbox.h"
#include "stillslam/core/work_queue.h"
#include "stillslam/core/worker.h"

namespace stillslam {
namespace {

using namespace std::chrono_literals;

TEST(WorkQueue, FifoAndStopDrainsBeforeEnd) {
  WorkQueue<int> q;
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(q.push(i));
  EXPECT_EQ(q.size(), 5u);
  EXPECT_EQ(*q.pop(), 0);
  q.stop();
  EXPECT_FALSE(q.push(9));
  std::vector<int> rest;
  while (auto v = q.pop()) rest.push_back(*v);
  EXPECT_EQ(rest, (std::vector<int>{1, 2, 3, 4}));
  EXPECT_FALSE(q.pop().has_value());
}

TEST(WorkQueue, BoundedPushWaitsForRoom) {
  WorkQueue<int> q(2);
  q.push(1);
  q.push(2);
  std::atomic<bool> third_in{false};
  std::thread producer([&] {
    q.push(3);
    third_in = true;
  });
  std::this_thread::sleep_for(50ms);
  EXPECT_FALSE(third_in.load());
  EXPECT_EQ(q.size(), 2u);
  EXPECT_EQ(*q.pop(), 1);
  producer.join();
  EXPECT_TRUE(third_in.load());
  EXPECT_EQ(q.take_all(), (std::deque<int>{2, 3}));
}

TEST(WorkQueue, StopWakesABlockedConsumer) {
  WorkQueue<int> q;
  auto consumer = std::async(std::launch::async, [&] { return q.pop(); });
  std::this_thread::sleep_for(20ms);
  q.stop();
  EXPECT_FALSE(consumer.get().has_value());
}

TEST(Worker, ThreadedHandlesInOrderAndStopFinishesTheQueue) {
  std::vector<int> seen;
  Worker<int> w(WorkerMode::Threaded, [&](int& v) {
    std::this_thread::sleep_for(1ms);
    seen.push_back(v);
  });
  for (int i = 0; i < 20; ++i) EXPECT_TRUE(w.submit(i));
  w.stop();
  ASSERT_EQ(seen.size(), 20u);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(seen[static_cast<std::size_t>(i)], i);
  EXPECT_FALSE(w.submit(99));
  EXPECT_TRUE(w.idle());
}

TEST(Worker, SynchronousRunsNothingUntilAsked) {
  std::vector<int> seen;
  Worker<int> w(WorkerMode::Synchronous, [&](int& v) { seen.push_back(v); });
  w.submit(1);
  w.submit(2);
  EXPECT_TRUE(seen.empty());
  EXPECT_EQ(w.queued(), 2u);
  EXPECT_FALSE(w.idle());
  w.run_pending();
  EXPECT_EQ(seen, (std::vector<int>{1, 2}));
  EXPECT_TRUE(w.idle());
  w.submit(3);
  w.stop();  // handles what is left
  EXPECT_EQ(seen, (std::vector<int>{1, 2, 3}));
}

TEST(Worker, HandlerMaySubmitMoreInSynchronousMode) {
  std::vector<int> seen;
  Worker<int>* self = nullptr;
  Worker<int> w(WorkerMode::Synchronous, [&](int& v) {
    seen.push_back(v);
    if (v < 3) self->submit(v + 1);
  });
  self = &w;
  w.submit(0);
  w.run_pending();
  EXPECT_EQ(seen, (std::vector<int>{0, 1, 2, 3}));
}

TEST(Worker, PauseLetsTheCurrentItemFinishAndHoldsTheNext) {
  std::promise<void> release_first;
  std::shared_future<void> first_released = release_first.get_future().share();
  std::atomic<int> started{0}, done{0};
  Worker<int> w(WorkerMode::Threaded, [&](int& v) {
    ++started;
    if (v == 0) first_released.wait();
    ++done;
  });
  w.submit(0);
  while (started.load() == 0) std::this_thread::sleep_for(1ms);
  w.submit(1);
  auto paused = std::async(std::launch::async, [&] { w.pause(); });
  std::this_thread::sleep_for(20ms);
  EXPECT_EQ(paused.wait_for(0ms), std::future_status::timeout);  // item 0 still running
  release_first.set_value();
  paused.get();
  EXPECT_EQ(done.load(), 1);
  std::this_thread::sleep_for(20ms);
  EXPECT_EQ(started.load(), 1);  // item 1 waits
  EXPECT_EQ(w.queued(), 1u);  // taken from the queue but held by the paused worker: still waiting
  EXPECT_FALSE(w.idle());
  w.resume();
  w.wait_idle();
  EXPECT_EQ(done.load(), 2);
}

TEST(Worker, CancelReturnsWhatWasNotStarted) {
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<int> started{0};
  std::vector<int> seen;
  Worker<int> w(WorkerMode::Threaded, [&](int& v) {
    ++started;
    released.wait();
    seen.push_back(v);
  });
  w.submit(0);
  while (started.load() == 0) std::this_thread::sleep_for(1ms);
  w.submit(1);
  w.submit(2);
  auto left = std::async(std::launch::async, [&] { return w.cancel(); });
  std::this_thread::sleep_for(20ms);
  release.set_value();
  EXPECT_EQ(left.get(), (std::deque<int>{1, 2}));
  EXPECT_EQ(seen, (std::vector<int>{0}));
  EXPECT_TRUE(w.idle());
  EXPECT_FALSE(w.submit(3));
}

TEST(Worker, WaitIdleReturnsAfterEverythingSubmittedIsHandled) {
  std::atomic<int> done{0};
  Worker<int> w(WorkerMode::Threaded, [&](int&) {
    std::this_thread::sleep_for(2ms);
    ++done;
  });
  for (int i = 0; i < 10; ++i) w.submit(i);
  w.wait_idle();
  EXPECT_EQ(done.load(), 10);
  EXPECT_EQ(w.queued(), 0u);
}

TEST(Mailbox, KeepsOnlyTheNewestAndCountsSkips) {
  Mailbox<int> box;
  EXPECT_FALSE(box.put(1));
  EXPECT_TRUE(box.put(2));
  EXPECT_TRUE(box.put(3));
  EXPECT_EQ(box.skipped(), 2u);
  EXPECT_EQ(*box.take(), 3);
  EXPECT_FALSE(box.try_take().has_value());
  auto consumer = std::async(std::launch::async, [&] { return box.take(); });
  std::this_thread::sleep_for(10ms);
  box.put(4);
  EXPECT_EQ(*consumer.get(), 4);
  box.stop();
  EXPECT_FALSE(box.put(5));
  EXPECT_FALSE(box.take().has_value());
}

TEST(LatestValue, ReadersSeeTheNewestVersion) {
  LatestValue<int> slot;
  EXPECT_EQ(slot.read().version, 0u);
  EXPECT_EQ(slot.read().value, nullptr);
  slot.publish(std::make_shared<const int>(7));
  slot.publish(std::make_shared<const int>(8));
  const auto r = slot.read();
  EXPECT_EQ(r.version, 2u);
  EXPECT_EQ(*r.value, 8);
  EXPECT_EQ(slot.wait_newer(2, 10ms).version, 2u);  // times out
  auto waiter = std::async(std::launch::async, [&] { return slot.wait_newer(2, 5000ms); });
  std::this_thread::sleep_for(10ms);
  slot.publish(std::make_shared<const int>(9));
  const auto newer = waiter.get();
  EXPECT_EQ(newer.version, 3u);
  EXPECT_EQ(*newer.value, 9);
  EXPECT_EQ(*r.value, 8);  // an old read keeps its snapshot
}

}  // namespace
}  // namespace stillslam
