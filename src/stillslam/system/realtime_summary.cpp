#include "stillslam/system/realtime_summary.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace stillslam {

RealtimeSummary summarize_realtime(const RunResult& result) {
  RealtimeSummary s;
  const std::size_t n = result.frames.size();
  s.fps = result.processing_seconds > 0 ? static_cast<double>(n) / result.processing_seconds : 0;
  std::vector<double> latency;
  latency.reserve(n);
  double age_sum = 0;
  for (const FrameStats& f : result.frames) {
    latency.push_back(f.latency_ms);
    if (f.build.mask_age == 0) ++s.fresh_masks;
    if (f.build.mask_age > 0) ++s.carried_masks;
    if (f.build.mask_age >= 0) age_sum += f.build.mask_age;
    s.max_mask_age = std::max(s.max_mask_age, f.build.mask_age);
    if (f.build.mask_waited) ++s.waited_frames;
    if (f.build.segmentation_request != ScheduleReason::None) ++s.segmentation_requests;
    s.segmentation_skips = std::max(s.segmentation_skips, f.build.segmentation_skips);
    if (f.keyframe_deferred) ++s.keyframes_deferred;
    if (f.keyframe_held) ++s.keyframes_held;
  }
  s.latency_ms = summarize_times(latency);
  if (!latency.empty()) {
    std::sort(latency.begin(), latency.end());
    s.latency_p99_ms = latency[std::min(n - 1, static_cast<std::size_t>(std::ceil(0.99 * n)) - 1)];
  }
  const std::size_t masked = s.fresh_masks + s.carried_masks;
  s.mean_mask_age = masked ? age_sum / static_cast<double>(masked) : 0;
  s.dropped_frames = result.dropped_frames;
  s.dropped_share = n + s.dropped_frames ? static_cast<double>(s.dropped_frames) / (n + s.dropped_frames) : 0;
  s.cpu_ms_per_frame = n ? 1000.0 * result.process_cpu_seconds / n : 0;
  s.mapping_cpu_ms_per_frame = summarize_local_bundle_adjustment(result.mapper, n).mapping_cpu_ms_per_frame;
  return s;
}

nlohmann::json to_json(const RealtimeSummary& s) {
  nlohmann::json latency = to_json(s.latency_ms);
  latency["p99"] = s.latency_p99_ms;
  return {{"fps", s.fps},
          {"latency_ms", latency},
          {"dropped_frames", s.dropped_frames},
          {"dropped_share", s.dropped_share},
          {"cpu_ms_per_frame", s.cpu_ms_per_frame},
          {"mapping_cpu_ms_per_frame", s.mapping_cpu_ms_per_frame},
          {"masks",
           {{"fresh", s.fresh_masks},
            {"carried", s.carried_masks},
            {"mean_age", s.mean_mask_age},
            {"max_age", s.max_mask_age},
            {"frames_waited", s.waited_frames},
            {"keyframes_deferred", s.keyframes_deferred},
            {"keyframes_held", s.keyframes_held},
            {"segmentation_requests", s.segmentation_requests},
            {"segmentation_skips", s.segmentation_skips}}}};
}

}  // namespace stillslam
