#pragma once
// `stillslam run --save-frames DIR`: writes the annotated frames
// (publish/frame_drawing.h) as PNG (lossless, the default) or JPEG files
// (about 15x faster to encode) named by input index and timestamp,
// frame_<index>_<seconds>.png, e.g. frame_000042_1305031102.175304.png.
//
// The run loop hands over the newest frame snapshot after each frame
// (System::publisher()); drawing and PNG encoding run on the saver's own
// thread, so tracking only copies a pointer. A bounded queue sits between:
// with `wait_when_full` (--deterministic) the run loop waits for room, so no
// frame is ever missed; otherwise a frame arriving while the queue is full is
// skipped and counted, so a slow disk never slows tracking.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>

#include "stillslam/core/work_queue.h"
#include "stillslam/publish/frame_drawing.h"
#include "stillslam/publish/snapshots.h"

namespace stillslam::apps {

struct FrameSaverOptions {
  std::filesystem::path dir;     // created when missing
  int every = 1;                 // save every Nth processed frame (1: all)
  bool wait_when_full = false;   // never skip a frame (deterministic runs)
  // Frames of an earlier run in `dir` (frame_*.png / .jpg) are removed; without
  // it they are an Error, so a report never mixes two runs' frames.
  bool replace = false;
  std::string format = "png";    // "png" or "jpg" (quality 90)
  std::size_t queue_frames = 8;  // snapshots waiting to be written
  FrameDrawingOptions drawing;
  void check() const;
};

class FrameSaver {
 public:
  // Creates `dir`; Error when it cannot, or when it holds earlier frames and not `replace`.
  explicit FrameSaver(FrameSaverOptions options);
  ~FrameSaver();
  FrameSaver(const FrameSaver&) = delete;
  FrameSaver& operator=(const FrameSaver&) = delete;

  // Called once per processed frame, in order; keeps every `every`th.
  void offer(std::shared_ptr<const FrameSnapshot> frame);
  // Writes what is queued and joins the thread. Idempotent.
  void finish();

  std::size_t written() const { return written_; }    // after finish()
  std::size_t skipped() const { return skipped_; }    // queue full (not wait_when_full)
  std::size_t failed() const { return failed_; }      // could not be written (warned)
  double mean_write_ms() const { return written_ ? write_ms_ / static_cast<double>(written_) : 0.0; }  // draw + encode + write, per frame
  const FrameSaverOptions& options() const { return options_; }

  // The file name of a frame: frame_<index, 6 digits>_<timestamp, 6 decimals>.<format>
  std::string file_name(const FrameSnapshot& frame) const;

 private:
  void run();

  FrameSaverOptions options_;
  WorkQueue<std::shared_ptr<const FrameSnapshot>> queue_;
  std::size_t offered_ = 0;
  std::size_t written_ = 0, skipped_ = 0, failed_ = 0;
  double write_ms_ = 0;
  std::thread thread_;
};

}  // namespace stillslam::apps
