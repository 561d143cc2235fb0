#pragma once
// Common part of the file-based readers: index checks and the
// skip_bad_frames policy around a format-specific read_frame().
#include "stillslam/io/dataset.h"

namespace stillslam {

class FileDataset : public Dataset {
 public:
  SensorFrame load(std::size_t i) const final;

 protected:
  explicit FileDataset(bool skip_bad_frames) : skip_bad_frames_(skip_bad_frames) {}
  // Reads frame i (i < size()); throws Error naming the file on bad input.
  virtual SensorFrame read_frame(std::size_t i) const = 0;
  // File name of frame i, for the invalid frame's `name`.
  virtual std::string frame_name(std::size_t i) const = 0;

 private:
  bool skip_bad_frames_;
};

}  // namespace stillslam
