#pragma once
// The part of stats.json that comes from a RunResult, one writer for `run`,
// the ROS 2 node and `bench` (what `stillslam report` reads): summary, end,
// map merges, local mapping, loop closing, map file and the per-frame list.
// Callers add what only they know (config, input, the signal that ended it).
#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

#include "stillslam/system/dataset_runner.h"

namespace stillslam {

// features_removed: per frame, the features the dynamic mask removed (the
// published snapshot's removed_keypoints); empty: not recorded.
nlohmann::json run_result_json(const RunResult& result, const std::vector<std::size_t>& features_removed);

}  // namespace stillslam
