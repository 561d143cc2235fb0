// results.json of the benchmark (part of report.h).
#include <algorithm>
#include <cmath>

#include "stillslam/eval/evaluation_report.h"
#include "stillslam/benchmark/report.h"

namespace stillslam {
namespace {

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

nlohmann::json accuracy_json(const AccuracyStats& a) {
  return {{"pairs", a.pairs},
          {"ape", to_json(a.ape)},
          {"rpe_trans", to_json(a.rpe_trans)},
          {"rpe_rot", to_json(a.rpe_rot)},
          {"rpe_trans_1s", to_json(a.rpe_trans_1s)},
          {"rpe_rot_1s", to_json(a.rpe_rot_1s)}};
}

nlohmann::json run_json(const RunRecord& r) {
  nlohmann::json j{{"run", r.run},
                   {"segmentation", r.segmentation},
                   {"frames", r.frames},
                   {"tracked", r.tracked},
                   {"lost_frames", r.lost_frames},
                   {"lost_episodes", r.lost_episodes},
                   {"keyframes", r.keyframes},
                   {"times_ms",
                    {{"per_frame", to_json(r.total_ms)},
                     {"tracker", to_json(r.tracker_ms)},
                     {"segmentation", to_json(r.segmentation_ms)},
                     {"segmentation_wait", to_json(r.segmentation_wait_ms)}}},
                   {"wall_seconds", r.wall_seconds},
                   {"local_ba", to_json(r.local_ba)},
                   {"mapping_cpu_ms_per_frame", r.local_ba.mapping_cpu_ms_per_frame},
                   {"trajectory", r.trajectory_file.string()},
                   {"failed", r.failed()}};
  if (r.error) j["error"] = *r.error;
  if (r.accuracy) j["accuracy"] = accuracy_json(*r.accuracy);
  if (r.evaluation_error) j["evaluation_error"] = *r.evaluation_error;
  return j;
}

nlohmann::json mode_json(const ModeResult& m) {
  nlohmann::json runs = nlohmann::json::array();
  for (const RunRecord& r : m.runs) runs.push_back(run_json(r));
  const RunRecord* median = m.median_run();
  return {{"segmentation", m.segmentation},
          {"segmentation_active", m.segmentation_active},
          {"median_run", median ? nlohmann::json(median->run) : nlohmann::json()},
          {"failed_runs", std::count_if(m.runs.begin(), m.runs.end(), [](const RunRecord& r) { return r.failed(); })},
          {"runs", std::move(runs)}};
}

// (off - on) / off of the median runs' statistics, percent.
nlohmann::json improvement_json(const SequenceResult& s) {
  const RunRecord* off = s.off.median_run();
  const RunRecord* on = s.on.median_run();
  nlohmann::json j = nlohmann::json::object();
  if (off == nullptr || on == nullptr || off->failed() || on->failed()) return j;
  const auto add = [&j](const std::string& key, const ErrorStatistics& a, const ErrorStatistics& b) {
    j[key] = {{"rmse", number_or_null(improvement_percent(a.rmse, b.rmse))},
              {"mean", number_or_null(improvement_percent(a.mean, b.mean))},
              {"median", number_or_null(improvement_percent(a.median, b.median))},
              {"std", number_or_null(improvement_percent(a.std, b.std))},
              {"min", number_or_null(improvement_percent(a.min, b.min))},
              {"max", number_or_null(improvement_percent(a.max, b.max))}};
  };
  add("ape", off->accuracy->ape, on->accuracy->ape);
  add("rpe_trans", off->accuracy->rpe_trans, on->accuracy->rpe_trans);
  add("rpe_rot", off->accuracy->rpe_rot, on->accuracy->rpe_rot);
  add("rpe_trans_1s", off->accuracy->rpe_trans_1s, on->accuracy->rpe_trans_1s);
  add("rpe_rot_1s", off->accuracy->rpe_rot_1s, on->accuracy->rpe_rot_1s);
  return j;
}

}  // namespace

nlohmann::json benchmark_to_json(const std::vector<SequenceResult>& results, const BenchmarkOptions& options) {
  nlohmann::json sequences = nlohmann::json::array();
  for (const SequenceResult& s : results) {
    nlohmann::json j{{"name", s.input.name},
                     {"folder", s.input.folder.string()},
                     {"config", s.input.config.string()},
                     {"groundtruth", s.input.groundtruth.string()},
                     {"dataset", s.dataset_kind},
                     {"sensor", s.sensor},
                     {"frames", s.dataset_frames},
                     {"groundtruth_poses", s.groundtruth.size()},
                     {"off", mode_json(s.off)},
                     {"on", mode_json(s.on)},
                     {"improvement_percent", improvement_json(s)}};
    if (s.error) j["error"] = *s.error;
    sequences.push_back(std::move(j));
  }
  const PosePairOptions per_second = rpe_per_second_pairs();
  return {{"benchmark",
           {{"runs_per_mode", options.runs},
            {"max_frames", options.max_frames ? nlohmann::json(*options.max_frames) : nlohmann::json()},
            {"deterministic", options.deterministic},
            {"realtime", false},
            {"median_selection", "median APE rmse per mode; failed runs rank last; even count: lower middle"},
            {"improvement", "(off - on) / off * 100"},
            {"ape", "translation, SE3 (Horn/Umeyama) alignment, TUM greedy association max_dt 0.02 s"},
            {"rpe_trans/rpe_rot", "consecutive 1-frame steps of the associated sequence (m, deg)"},
            {"rpe_trans_1s/rpe_rot_1s",
             "every start pose to the pose " + std::to_string(per_second.delta) +
                 " s later, as TUM evaluate_rpe.py --fixed_delta --delta 1 --delta_unit s (m, deg per second)"}}},
          {"sequences", std::move(sequences)}};
}

}  // namespace stillslam
