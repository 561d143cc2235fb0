#include "stillslam/system/run_summary.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace stillslam {

TimingSummary summarize_times(std::vector<double> v) {
  TimingSummary t;
  if (v.empty()) return t;
  std::sort(v.begin(), v.end());
  t.mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
  const std::size_t n = v.size();
  t.median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  t.p95 = v[std::min(n - 1, static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(n))) - 1)];
  t.max = v.back();
  return t;
}

RunSummary summarize_run(const std::vector<FrameStats>& frames) {
  RunSummary s;
  s.frames = frames.size();
  std::vector<double> total, tracking, extraction, wait, total_cpu, tracking_cpu, extraction_cpu, propagation_cpu, core_wait;
  double before = 0, after = 0, inliers = 0;
  for (const FrameStats& f : frames) {
    s.tracked += f.has_pose ? 1 : 0;
    s.lost += f.state == TrackingState::Lost ? 1 : 0;
    s.keyframes_inserted += f.keyframe ? 1 : 0;
    total.push_back(f.total_ms);
    tracking.push_back(f.tracking_ms);
    extraction.push_back(f.build.extraction_ms);
    wait.push_back(f.build.segmentation_wait_ms);
    total_cpu.push_back(f.total_cpu_ms);
    tracking_cpu.push_back(f.tracking_cpu_ms);
    extraction_cpu.push_back(f.build.extraction_cpu_ms);
    propagation_cpu.push_back(f.build.propagation_cpu_ms);
    core_wait.push_back(f.core_wait_ms);
    before += f.build.keypoints_before;
    after += f.build.keypoints_after;
    inliers += f.inliers;
  }
  s.total_ms = summarize_times(total);
  s.tracking_ms = summarize_times(tracking);
  s.extraction_ms = summarize_times(extraction);
  s.segmentation_wait_ms = summarize_times(wait);
  s.total_cpu_ms = summarize_times(total_cpu);
  s.tracking_cpu_ms = summarize_times(tracking_cpu);
  s.extraction_cpu_ms = summarize_times(extraction_cpu);
  s.propagation_cpu_ms = summarize_times(propagation_cpu);
  s.core_wait_ms = summarize_times(core_wait);
  s.extraction_share = s.total_ms.mean > 0 ? s.extraction_ms.mean / s.total_ms.mean : 0;
  if (!frames.empty()) {
    const double n = static_cast<double>(frames.size());
    s.mean_keypoints_before = before / n;
    s.mean_keypoints_after = after / n;
    s.mean_inliers = inliers / n;
  }
  return s;
}

double sequence_seconds(const std::vector<FrameStats>& frames) {
  if (frames.size() < 2) return 0;
  const double span = frames.back().timestamp - frames.front().timestamp;
  return span > 0 ? span * static_cast<double>(frames.size()) / static_cast<double>(frames.size() - 1) : 0;
}

LocalBundleAdjustmentSummary summarize_local_bundle_adjustment(const LocalMapperStats& stats, std::size_t frames,
                                                               double seconds) {
  LocalBundleAdjustmentSummary s;
  s.runs = stats.bundle_adjustments;
  s.aborted = stats.bundle_adjustments_aborted;
  s.aborted_by_tracking = stats.bundle_adjustments_aborted_by_tracking;
  s.aborted_by_pause = stats.bundle_adjustments_aborted_by_pause;
  s.cut_short = stats.bundle_adjustments_cut_short;
  s.discarded = stats.bundle_adjustments_discarded;
  s.skipped = stats.bundle_adjustments_skipped;
  s.aborted_share = s.runs ? static_cast<double>(s.aborted) / s.runs : 0;
  s.discarded_share = s.runs ? static_cast<double>(s.discarded) / s.runs : 0;
  std::vector<double> ms, cpu, kf, fixed, points, obs, it;
  for (const LocalBundleAdjustmentRecord& r : stats.bundle_adjustment_runs) {
    ms.push_back(r.ms);
    cpu.push_back(r.cpu_ms);
    kf.push_back(r.keyframes);
    fixed.push_back(r.fixed_keyframes);
    points.push_back(r.points);
    obs.push_back(r.observations);
    it.push_back(r.iterations);
  }
  s.ms = summarize_times(ms);
  s.cpu_ms = summarize_times(cpu);
  s.keyframes = summarize_times(kf);
  s.fixed_keyframes = summarize_times(fixed);
  s.points = summarize_times(points);
  s.observations = summarize_times(obs);
  s.iterations = summarize_times(it);
  s.mapping_cpu_ms_per_frame = frames ? stats.cpu_ms / static_cast<double>(frames) : 0;
  s.keyframes_per_second = seconds > 0 ? stats.keyframes / seconds : 0;
  return s;
}

nlohmann::json to_json(const LocalBundleAdjustmentSummary& s) {
  return {{"runs", s.runs},
          {"aborted", s.aborted},
          {"aborted_by_tracking", s.aborted_by_tracking},
          {"aborted_by_pause", s.aborted_by_pause},
          {"cut_short", s.cut_short},
          {"discarded", s.discarded},
          {"discarded_share", s.discarded_share},
          {"skipped", s.skipped},
          {"aborted_share", s.aborted_share},
          {"ms", to_json(s.ms)},
          {"cpu_ms", to_json(s.cpu_ms)},
          {"window_keyframes", to_json(s.keyframes)},
          {"window_fixed_keyframes", to_json(s.fixed_keyframes)},
          {"window_points", to_json(s.points)},
          {"window_observations", to_json(s.observations)},
          {"iterations", to_json(s.iterations)}};
}

nlohmann::json to_json(const FrameStats& f) {
  return {{"index", f.index},
          {"timestamp", f.timestamp},
          {"state", to_string(f.state)},
          {"reason", f.reason},
          {"has_pose", f.has_pose},
          {"posed_at_start", f.posed_at_start},
          {"map_id", f.map_id},
          {"keyframe", f.keyframe},
          {"keyframe_deferred", f.keyframe_deferred},
          {"keyframe_held", f.keyframe_held},
          {"held_points_removed", f.held_points_removed},
          {"motion_prior", {{"applied", f.motion_prior.applied}, {"offset_m", f.motion_prior.offset},
                            {"rejected_share", f.motion_prior.rejected_share},
                            {"refit_offset_m", f.motion_prior.refit_offset}}},
          {"fresh_mask_culled", f.fresh_mask_culled},
          {"mask_age", f.build.mask_age},
          {"mask_fresh", f.build.mask_age == 0},
          {"mask_waited", f.build.mask_waited},
          {"segmentation_request", to_string(f.build.segmentation_request)},
          {"segmentation_skips", f.build.segmentation_skips},
          {"features_before_filter", f.build.keypoints_before},
          {"features_after_filter", f.build.keypoints_after},
          {"features_with_depth", f.build.keypoints_with_depth},
          {"matches", f.matches},
          {"inliers", f.inliers},
          {"detections", f.build.detections},
          {"mask_coverage", f.build.mask_coverage},
          {"held_mask_coverage", f.build.held_coverage},
          {"motion",
           {{"judged", f.build.motion.judged},
            {"static_instances", f.build.motion.static_instances},
            {"moving_instances", f.build.motion.moving_instances},
            {"predicted_moving_instances", f.build.motion.predicted_moving_instances},
            {"features_removed_by_class", f.build.motion.features_removed_by_class},
            {"features_removed_by_motion", f.build.motion.features_removed_by_motion},
            {"features_kept_by_motion", f.build.motion.features_kept_by_motion},
            {"instance_features", f.build.motion.instance_features},
            {"map_points_culled", f.build.motion.map_points_culled},
            {"sparse_view", f.build.motion.sparse_view}}},
          {"times_ms",
           {{"extraction", f.build.extraction_ms},
            {"segmentation", f.build.segmentation_ms},
            {"segmentation_cpu", f.build.segmentation_cpu_ms},
            {"segmentation_wait", f.build.segmentation_wait_ms},
            {"association", f.build.association_ms},
            {"frame_build", f.build.total_ms},
            {"tracking", f.tracking_ms},
            {"mapping_inline", f.mapping_ms},
            {"total", f.total_ms},
            {"extraction_cpu", f.build.extraction_cpu_ms},
            {"propagation_cpu", f.build.propagation_cpu_ms},
            {"tracking_cpu", f.tracking_cpu_ms},
            {"total_cpu", f.total_cpu_ms},
            {"core_wait", f.core_wait_ms},
            {"publish", f.publish_ms},
            {"latency", f.latency_ms}}},
          {"loops_closed", f.loops_closed},
          {"global_bundle_adjustment_running", f.global_bundle_adjustment_running}};
}

nlohmann::json to_json(const TimingSummary& t) {
  return {{"mean", t.mean}, {"median", t.median}, {"p95", t.p95}, {"max", t.max}};
}

nlohmann::json to_json(const RunSummary& s) {
  return {{"frames", s.frames},
          {"tracked", s.tracked},
          {"tracked_ratio", s.tracked_ratio()},
          {"lost", s.lost},
          {"keyframes_inserted", s.keyframes_inserted},
          {"mean_features_before_filter", s.mean_keypoints_before},
          {"mean_features_after_filter", s.mean_keypoints_after},
          {"mean_inliers", s.mean_inliers},
          {"times_ms",
           {{"total", to_json(s.total_ms)},
            {"tracking", to_json(s.tracking_ms)},
            {"extraction", to_json(s.extraction_ms)},
            {"segmentation_wait", to_json(s.segmentation_wait_ms)},
            {"total_cpu", to_json(s.total_cpu_ms)},
            {"tracking_cpu", to_json(s.tracking_cpu_ms)},
            {"extraction_cpu", to_json(s.extraction_cpu_ms)},
            {"propagation_cpu", to_json(s.propagation_cpu_ms)},
            {"core_wait", to_json(s.core_wait_ms)}}},
          {"extraction_share", s.extraction_share}};
}

nlohmann::json to_json(const LocalMapperStats& s, std::size_t frames, double seconds) {
  const LocalBundleAdjustmentSummary ba = summarize_local_bundle_adjustment(s, frames, seconds);
  nlohmann::json runs = nlohmann::json::array();
  for (const LocalBundleAdjustmentRecord& r : s.bundle_adjustment_runs) {
    runs.push_back({{"keyframes", r.keyframes},
                    {"fixed_keyframes", r.fixed_keyframes},
                    {"points", r.points},
                    {"observations", r.observations},
                    {"iterations", r.iterations},
                    {"ms", r.ms},
                    {"cpu_ms", r.cpu_ms},
                    {"aborted", r.aborted},
                    {"cut_short", r.cut_short},
                    {"abort_cause", to_string(r.abort_cause)}});
  }
  return {{"keyframes", s.keyframes},
          {"points_created", s.points_created},
          {"points_culled", s.points_culled},
          {"keyframes_culled", s.keyframes_culled},
          {"bundle_adjustments", s.bundle_adjustments},
          {"bundle_adjustments_aborted", s.bundle_adjustments_aborted},
          {"bundle_adjustments_skipped", s.bundle_adjustments_skipped},
          {"bundle_adjustment_ms_total", s.bundle_adjustment_ms},
          {"total_ms", s.total_ms},
          {"cpu_ms_total", s.cpu_ms},
          {"cpu_ms_per_frame", ba.mapping_cpu_ms_per_frame},
          {"modelled_busy_ms_total", s.modelled_busy_ms},
          {"cpu_ms_by_step",
           {{"registration", s.cpu_by_step.registration},
            {"triangulation", s.cpu_by_step.triangulation},
            {"fusion", s.cpu_by_step.fusion},
            {"bundle_adjustment", s.cpu_by_step.bundle_adjustment},
            {"keyframe_culling", s.cpu_by_step.keyframe_culling}}},
          {"keyframes_per_second", ba.keyframes_per_second},
          {"local_ba", to_json(ba)},
          {"local_ba_runs", std::move(runs)}};
}

nlohmann::json to_json(const LoopCloserStats& s) {
  return {{"keyframes", s.keyframes},
          {"loops_closed", s.loops_closed},
          {"global_bundle_adjustments", s.global_bundle_adjustments},
          {"global_bundle_adjustments_aborted", s.global_bundle_adjustments_aborted},
          {"detection_ms_total", s.detection_ms},
          {"correction_ms_total", s.correction_ms},
          {"global_bundle_adjustment_ms_total", s.global_bundle_adjustment_ms}};
}

}  // namespace stillslam
