#include "stillslam/system/run_result_json.h"

#include "stillslam/system/realtime_summary.h"
#include "stillslam/system/run_summary.h"

namespace stillslam {

nlohmann::json run_result_json(const RunResult& result, const std::vector<std::size_t>& features_removed) {
  nlohmann::json stats;
  nlohmann::json& summary = stats["summary"] = to_json(summarize_run(result.frames));
  summary["wall_seconds"] = result.wall_seconds;
  summary["dropped_frames"] = result.dropped_frames;
  summary["skipped_frames"] = result.skipped_frames;
  if (result.preloaded_frames > 0) {
    summary["preload"] = {{"frames", result.preloaded_frames},
                          {"bytes", result.preloaded_bytes},
                          {"seconds", result.preload_seconds}};
  }
  summary["interrupted"] = result.interrupted;
  summary["keyframes_in_map"] = result.keyframes.size();
  summary["map_points"] = result.map_points;
  summary["maps"] = result.maps;
  summary["new_maps"] = result.new_maps;
  summary["relocalizations"] = result.relocalizations;
  if (result.error) summary["error"] = *result.error;
  summary["realtime"] = to_json(summarize_realtime(result));
  stats["end"] = {{"reason", to_string(result.end)},
                  {"frames_processed", result.frames.size()},
                  {"frames_in_input", result.frames_in_input}};
  nlohmann::json merges = nlohmann::json::array();
  for (const MapMergeStats& m : result.merges) {
    merges.push_back({{"source_map", m.source_map}, {"target_map", m.target_map}, {"query_keyframe", m.query_id},
                      {"recognized_keyframe", m.loop_id}, {"inliers", m.inliers}, {"fused_points", m.fused_points},
                      {"moved_keyframes", m.moved_keyframes}, {"welding_keyframes", m.welding_keyframes}});
  }
  stats["map_merges"] = std::move(merges);
  stats["local_mapping"] = to_json(result.mapper, result.frames.size(), sequence_seconds(result.frames));
  stats["loop_closing_stats"] = to_json(result.loop_closer);
  if (result.map_file) {
    stats["map_file"] = {{"bytes", result.map_file->bytes}, {"maps", result.map_file->maps},
                         {"keyframes", result.map_file->keyframes}, {"map_points", result.map_file->map_points},
                         {"points_on_people", result.map_file->points_on_people}, {"save_ms", result.save_map_ms}};
  }
  if (result.map_file_error) stats["map_file_error"] = *result.map_file_error;
  nlohmann::json frames = nlohmann::json::array();
  for (const FrameStats& f : result.frames) frames.push_back(to_json(f));
  for (std::size_t i = 0; i < frames.size() && i < features_removed.size(); ++i) {
    frames[i]["features_removed"] = features_removed[i];
  }
  stats["frames"] = std::move(frames);
  return stats;
}

}  // namespace stillslam
