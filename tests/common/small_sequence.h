#pragma once
// A small walking_xyz render for command-line tests (tests that run the
// built binary on a sequence written to disk).
#include <filesystem>

#include "stillslam/sim/sequence_writer.h"

namespace stillslam::test {

// 400x300, one ray per pixel, in DIR/seq; `people`: the two walking people.
inline sim::SequenceSummary write_small_sequence(const std::filesystem::path& dir, int frames, bool people) {
  sim::SimulationOptions opts;
  opts.trajectory = "walking_xyz";
  opts.frames = frames;
  opts.width = 400;
  opts.height = 300;
  opts.no_people = !people;
  opts.supersampling = 1;
  opts.data_dir = std::filesystem::path(STILLSLAM_SOURCE_DIR) / "data";
  return sim::write_sequence(dir / "seq", opts);
}

}  // namespace stillslam::test
