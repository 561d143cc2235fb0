#pragma once
// A progress line for long runs: a reader of the publish layer on its own
// thread. On a terminal it rewrites one line twice a second; otherwise (a
// log file, CI) it prints a plain line every `plain_interval`.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

#include "stillslam/publish/publisher.h"

namespace stillslam {

struct ProgressOptions {
  std::size_t total_frames = 0;  // frames the run will process (0: unknown, no ETA)
  bool terminal = false;         // rewrite one line in place
  std::chrono::milliseconds terminal_interval{500};
  std::chrono::milliseconds plain_interval{10000};
};

// "frame 120/827 (14.5%)  6.2 fps  ok  map 0: 41 kf, 3204 pts  ETA 1m54s"
// `frames_done` frames in `elapsed_s` seconds; atlas may be null.
std::string format_progress(const FrameSnapshot& frame, const AtlasSnapshot* atlas, std::size_t frames_done,
                            std::size_t total_frames, double elapsed_s);

class ProgressReporter {
 public:
  ProgressReporter(const Publisher& publisher, ProgressOptions options, std::FILE* out = stderr);
  ~ProgressReporter();  // stop()
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  // Prints the last line (ended by a newline on a terminal) and joins. Idempotent.
  void stop();

 private:
  void run();
  void print(bool final_line);

  const Publisher& publisher_;
  ProgressOptions options_;
  std::FILE* out_;
  std::chrono::steady_clock::time_point start_;
  std::uint64_t printed_version_ = 0;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread thread_;  // last: starts after the members above exist
};

}  // namespace stillslam
