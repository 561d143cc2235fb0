#pragma once
// Which pose pairs (i, j) the relative pose error compares, following evo's
// filters: by index distance, by travelled path length, or by elapsed time.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "stillslam/io/trajectory.h"

namespace stillslam {

enum class DeltaUnit { Frames, Seconds, Meters };

DeltaUnit parse_delta_unit(const std::string& name);  // "frames", "s", "m"
std::string to_string(DeltaUnit unit);

struct PosePairOptions {
  double delta = 1;
  DeltaUnit unit = DeltaUnit::Frames;
  // false: consecutive, non-overlapping steps (evo's default);
  // true: every start pose (TUM evaluate_rpe.py style).
  bool all_pairs = false;
  // Relative tolerance on delta for all-pairs in metres/seconds (evo: 0.1).
  double relative_tolerance = 0.1;
};

using PosePair = std::pair<std::size_t, std::size_t>;

// Pairs over `poses` (usually the ground truth of the associated sequence, as evo
// measures path length on the reference). Error for a non-positive or
// non-finite delta, or a fractional one in frames.
std::vector<PosePair> select_pose_pairs(const Trajectory& poses, const PosePairOptions& options);

}  // namespace stillslam
