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
  TimingSummary propagation_cpu_ms;  // async segmentation: carrying masks (calling thread's CPU)
  TimingSummary core_wait_ms;        // of total_ms, waiting for a core (FrameStats::core_wait_ms)
  double extraction_share = 0;  // mean extraction / mean total
  double mean_keypoints_before = 0, mean_keypoints_after = 0, mean_inliers = 0;
  double tracked_ratio() const { return frames ? static_cast<double>(tracked) / frames : 0.0; }
};
RunSummary summarize_run(const std::vector<FrameStats>& frames);

// The input time the frames span: first to last timestamp plus one frame
// interval (0 for fewer than two frames).
double sequence_seconds(const std::vector<FrameStats>& frames);

// Local BA over a run (issue #21): time per BA (wall and mapping-thread CPU),
// the aborted share (and why), window sizes and Ceres iterations (each as
// median / p95 / max), the mapping thread's CPU time per input frame and the
// keyframes it processed per second of input.
struct LocalBundleAdjustmentSummary {
  int runs = 0, aborted = 0, skipped = 0;
  int aborted_by_tracking = 0, aborted_by_pause = 0;
  // Aborted ones split: progress applied (cut short) or none kept (discarded).
  int cut_short = 0, discarded = 0;
  double aborted_share = 0;    // aborted / runs
  double discarded_share = 0;  // discarded / runs
  TimingSummary ms, cpu_ms, keyframes, fixed_keyframes, points, observations, iterations;
  double mapping_cpu_ms_per_frame = 0;
  double keyframes_per_second = 0;  // 0 when seconds is 0
};
LocalBundleAdjustmentSummary summarize_local_bundle_adjustment(const LocalMapperStats& stats, std::size_t frames,
                                                               double seconds = 0);

nlohmann::json to_json(const FrameStats& stats);
nlohmann::json to_json(const TimingSummary& t);
nlohmann::json to_json(const RunSummary& s);
// frames: the frames the run processed (for the mapping CPU per frame);
// seconds: the input time they span (for keyframes per second).
nlohmann::json to_json(const LocalMapperStats& s, std::size_t frames, double seconds = 0);
nlohmann::json to_json(const LocalBundleAdjustmentSummary& s);
nlohmann::json to_json(const LoopCloserStats& s);

}  // namespace stillslam
