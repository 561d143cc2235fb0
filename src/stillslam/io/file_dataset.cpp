#include "stillslam/io/file_dataset.h"

#include <spdlog/spdlog.h>

#include "stillslam/core/error.h"

namespace stillslam {

SensorFrame FileDataset::load(std::size_t i) const {
  if (i >= size()) {
    throw Error(kind() + " dataset: frame index " + std::to_string(i) + " is out of range (the sequence has " +
                std::to_string(size()) + " frames)");
  }
  try {
    SensorFrame frame = read_frame(i);
    frame.index = i;
    frame.timestamp = timestamp(i);
    return frame;
  } catch (const Error& e) {
    if (!skip_bad_frames_) throw;
    count_skip();
    spdlog::warn("skipping bad frame {} ({} skipped so far): {}", i, skipped_frames(), e.what());
    SensorFrame frame;
    frame.index = i;
    frame.timestamp = timestamp(i);
    frame.name = frame_name(i);
    frame.valid = false;
    frame.error = e.what();
    return frame;
  }
}

}  // namespace stillslam
