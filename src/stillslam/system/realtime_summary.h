#pragma once
// How a run kept up with its input (issue #16): sustained rate, latency from
// frame arrival to pose, frames dropped (--realtime), CPU per frame of the
// whole process, and where the frames' dynamic masks came from.
#include <cstddef>

#include <nlohmann/json.hpp>

#include "stillslam/system/dataset_runner.h"
#include "stillslam/system/run_summary.h"

namespace stillslam {

struct RealtimeSummary {
  double fps = 0;  // frames processed / processing seconds
  TimingSummary latency_ms;
  double latency_p99_ms = 0;
  std::size_t dropped_frames = 0;
  double dropped_share = 0;  // dropped / (processed + dropped)
  double cpu_ms_per_frame = 0;  // every thread of the process
  double mapping_cpu_ms_per_frame = 0;  // local mapping thread (issue #21's budget)
  // Masks: frames with a mask of their own (age 0), carried ones, the mean
  // and largest age, frames that waited for a mask, requests to the
  // asynchronous stage and how many it skipped as stale.
  std::size_t fresh_masks = 0, carried_masks = 0, waited_frames = 0, keyframes_deferred = 0,
              keyframes_held = 0;
  double mean_mask_age = 0;
  int max_mask_age = 0;
  std::size_t segmentation_requests = 0, segmentation_skips = 0;
};

RealtimeSummary summarize_realtime(const RunResult& result);
nlohmann::json to_json(const RealtimeSummary& s);

}  // namespace stillslam
