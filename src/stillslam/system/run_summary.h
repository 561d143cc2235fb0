#pragma once
// Summaries of a run's per-frame stats (for stats.json, the run command's
// closing lines and benchmarks).
#include <nlohmann/json.hpp>
#include <vector>

#include "stillslam/loop/loop_closer.h"
#include "stillslam/mapping/local_mapper.h"
#include "stillslam/system/frame_stats.h"

namespace stillslam {

struct TimingSummary {
  double mean = 0, median = 0, p95 = 0, max = 0;
};
TimingSummary summarize_times(std::vector<double> values_ms);

struct RunSummary {
  std::size_t frames = 0;
  std::size_t tracked = 0;  // frames with a pose
  std::size_t lost = 0;     // frames in the Lost state
  std::size_t keyframes_inserted = 0;
  TimingSummary total_ms, tracking_ms, extraction_ms, segmentation_wait_ms;
  TimingSummary total_cpu_ms, tracking_cpu_ms, extraction_cpu_ms;  // calling thread's CPU time
  double extraction_share = 0;  // mean extraction / mean total
  double mean_keypoints_before = 0, mean_keypoints_after = 0, mean_inliers = 0;
  double tracked_ratio() const { return frames ? static_cast<double>(tracked) / frames : 0.0; }
};
RunSummary summarize_run(const std::vector<FrameStats>& frames);

nlohmann::json to_json(const FrameStats& stats);
nlohmann::json to_json(const TimingSummary& t);
nlohmann::json to_json(const RunSummary& s);
nlohmann::json to_json(const LocalMapperStats& s);
nlohmann::json to_json(const LoopCloserStats& s);

}  // namespace stillslam
