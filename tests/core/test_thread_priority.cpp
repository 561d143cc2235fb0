// Per-thread priorities (core/thread_priority.h): a thread lowers its own
// priority, the others keep theirs.
#include "stillslam/core/thread_priority.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <thread>

#include "stillslam/core/thread_run_queue_wait.h"
#include "stillslam/core/worker.h"

namespace stillslam {
namespace {

#if defined(__linux__)

TEST(ThreadPriority, ANewThreadLowersItsOwnPriorityOnly) {
  const std::optional<int> before = this_thread_nice();
  ASSERT_TRUE(before.has_value());
  std::optional<int> inherited, after;
  std::string failed = "not run";
  std::thread t([&] {
    inherited = this_thread_nice();
    failed = lower_this_thread_priority(5);
    after = this_thread_nice();
  });
  t.join();
  EXPECT_EQ(failed, "");
  EXPECT_EQ(inherited, before);
  EXPECT_EQ(after, std::min(*before + 5, kMaxNice));
  EXPECT_EQ(this_thread_nice(), before);  // the creating thread is unchanged
}

TEST(ThreadPriority, CappedAtTheLowestPriorityAndZeroChangesNothing) {
  std::optional<int> capped, unchanged, start;
  std::string failed_cap = "not run", failed_zero = "not run";
  std::thread t([&] {
    start = this_thread_nice();
    failed_zero = lower_this_thread_priority(0);
    unchanged = this_thread_nice();
    failed_cap = lower_this_thread_priority(100);
    capped = this_thread_nice();
  });
  t.join();
  EXPECT_EQ(failed_zero, "");
  EXPECT_EQ(unchanged, start);
  EXPECT_EQ(failed_cap, "");
  EXPECT_EQ(capped, kMaxNice);
}

TEST(ThreadPriority, AThreadedWorkerRunsItsStartHookOnItsOwnThread) {
  const int main_nice = this_thread_nice().value();
  std::optional<int> seen;
  {
    Worker<int> worker(
        WorkerMode::Threaded, [&](int&) { seen = this_thread_nice(); }, 0,
        [] { EXPECT_EQ(lower_this_thread_priority(3), ""); });
    worker.submit(1);
    worker.wait_idle();
  }
  EXPECT_EQ(seen, std::min(main_nice + 3, kMaxNice));
  EXPECT_EQ(this_thread_nice(), main_nice);
  // Synchronous mode: the items run on the owner's thread, the hook never.
  bool hook_ran = false;
  Worker<int> sync(WorkerMode::Synchronous, [&](int&) { seen = this_thread_nice(); }, 0, [&] { hook_ran = true; });
  sync.submit(1);
  sync.run_pending();
  EXPECT_FALSE(hook_ran);
  EXPECT_EQ(seen, main_nice);
}

TEST(ThreadRunQueueWait, ReadForTheCallingThreadAndNeverDecreasing) {
  const std::optional<double> first = this_thread_run_queue_wait_ms();
  ASSERT_TRUE(first.has_value());
  EXPECT_GE(*first, 0.0);
  volatile double x = 0;
  for (int i = 0; i < 1000000; ++i) x = x + 1;
  const std::optional<double> second = this_thread_run_queue_wait_ms();
  ASSERT_TRUE(second.has_value());
  EXPECT_GE(*second, *first);
}

#endif

}  // namespace
}  // namespace stillslam
