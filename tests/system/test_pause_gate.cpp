// The run loop's pause gate: pause holds, step lets exactly one frame
// through, resume releases, a stop request ends the wait.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "stillslam/system/pause_gate.h"

namespace stillslam {
namespace {

using namespace std::chrono_literals;

// Waits (bounded) until `passed` frames went through the gate.
bool reaches(const PauseGate& gate, std::uint64_t passed) {
  for (int i = 0; i < 500 && gate.passed() < passed; ++i) std::this_thread::sleep_for(2ms);
  return gate.passed() == passed;
}

TEST(PauseGate, PauseStepResume) {
  PauseGate gate;
  std::atomic<bool> stop{false};
  EXPECT_TRUE(gate.wait(&stop));  // running: passes at once
  gate.pause();
  EXPECT_TRUE(gate.paused());
  std::atomic<int> frames{0};
  std::thread loop([&] {
    while (gate.wait(&stop, 5ms)) ++frames;
  });
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(frames, 0);
  gate.step();
  ASSERT_TRUE(reaches(gate, 2));
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(frames, 1);  // one frame per step, then held again
  EXPECT_TRUE(gate.paused());
  gate.step();
  gate.step();
  ASSERT_TRUE(reaches(gate, 4));
  EXPECT_EQ(frames, 3);
  gate.resume();
  for (int i = 0; i < 500 && frames < 100; ++i) std::this_thread::sleep_for(2ms);
  EXPECT_GE(frames, 100);
  gate.pause();
  stop = true;  // a paused wait ends on a stop request
  loop.join();
  EXPECT_FALSE(gate.wait(&stop));
}

TEST(PauseGate, StepWhileRunningPauses) {
  PauseGate gate;
  gate.step();
  EXPECT_TRUE(gate.paused());
  std::atomic<bool> stop{true};
  EXPECT_FALSE(gate.wait(&stop));  // paused, no step pending, stop set
}

}  // namespace
}  // namespace stillslam
