// report.md of the benchmark and its summary table (part of report.h).
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "stillslam/benchmark/report.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

std::string num(double v, int precision) {
  if (!std::isfinite(v)) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", precision, v);
  return buf;
}

std::string pct(double v) {
  if (!std::isfinite(v)) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%+.1f %%", v);
  return buf;
}

const AccuracyStats* median_accuracy(const ModeResult& m) {
  const RunRecord* r = m.median_run();
  return r != nullptr && !r->failed() ? &*r->accuracy : nullptr;
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A statistic of the median run, NaN without one.
template <typename Get>
double stat(const ModeResult& m, Get get) {
  const AccuracyStats* a = median_accuracy(m);
  return a != nullptr ? get(*a) : kNaN;
}

std::string tracked_cell(const ModeResult& m) {
  const RunRecord* r = m.median_run();
  if (r == nullptr) return "n/a";
  return std::to_string(r->tracked) + "/" + std::to_string(r->frames);
}

std::string lost_cell(const ModeResult& m) {
  const RunRecord* r = m.median_run();
  if (r == nullptr) return "n/a";
  return std::to_string(r->lost_frames) + "/" + std::to_string(r->lost_episodes);
}

double time_of(const ModeResult& m) {
  const RunRecord* r = m.median_run();
  return r != nullptr && r->frames > 0 ? r->total_ms.mean : kNaN;
}

std::string failed_note(const ModeResult& m) {
  std::size_t failed = 0;
  for (const RunRecord& r : m.runs) failed += r.failed() ? 1 : 0;
  return failed == 0 ? "" : " (" + std::to_string(failed) + "/" + std::to_string(m.runs.size()) + " failed)";
}

struct MetricRow {
  const char* name;
  const ErrorStatistics AccuracyStats::*member;
  int precision;
};
constexpr MetricRow kMetrics[] = {
    {"APE [m]", &AccuracyStats::ape, 4},
    {"RPE trans per frame [m]", &AccuracyStats::rpe_trans, 4},
    {"RPE rot per frame [deg]", &AccuracyStats::rpe_rot, 3},
    {"RPE trans per second [m/s]", &AccuracyStats::rpe_trans_1s, 4},
    {"RPE rot per second [deg/s]", &AccuracyStats::rpe_rot_1s, 3},
};

void accuracy_table(std::ostringstream& md, const SequenceResult& s) {
  const AccuracyStats* off = median_accuracy(s.off);
  const AccuracyStats* on = median_accuracy(s.on);
  md << "| metric | mode | rmse | mean | median | std | min | max |\n";
  md << "|---|---|---:|---:|---:|---:|---:|---:|\n";
  using Field = double ErrorStatistics::*;
  const Field fields[] = {&ErrorStatistics::rmse, &ErrorStatistics::mean, &ErrorStatistics::median,
                          &ErrorStatistics::std,  &ErrorStatistics::min,  &ErrorStatistics::max};
  for (const MetricRow& m : kMetrics) {
    const auto row = [&](const char* mode, const AccuracyStats* a) {
      md << "| " << m.name << " | " << mode;
      for (Field f : fields) md << " | " << (a ? num((a->*(m.member)).*f, m.precision) : "n/a");
      md << " |\n";
    };
    row("off (baseline)", off);
    row("on (ours)", on);
    md << "| " << m.name << " | improvement";
    for (Field f : fields) {
      md << " | " << (off && on ? pct(improvement_percent((off->*(m.member)).*f, (on->*(m.member)).*f)) : "n/a");
    }
    md << " |\n";
  }
}

void timing_table(std::ostringstream& md, const SequenceResult& s) {
  const RunRecord* off = s.off.median_run();
  const RunRecord* on = s.on.median_run();
  const auto cell = [](const RunRecord* r, auto get, int precision) {
    return r != nullptr ? num(get(*r), precision) : std::string("n/a");
  };
  md << "| median run | off (baseline) | on (ours) |\n|---|---:|---:|\n";
  md << "| time per frame mean [ms] (frame building + tracking) | "
     << cell(off, [](const RunRecord& r) { return r.total_ms.mean; }, 1) << " | "
     << cell(on, [](const RunRecord& r) { return r.total_ms.mean; }, 1) << " |\n";
  md << "| time per frame median [ms] | " << cell(off, [](const RunRecord& r) { return r.total_ms.median; }, 1)
     << " | " << cell(on, [](const RunRecord& r) { return r.total_ms.median; }, 1) << " |\n";
  md << "| tracker alone mean / median [ms] | "
     << (off ? num(off->tracker_ms.mean, 1) + " / " + num(off->tracker_ms.median, 1) : "n/a") << " | "
     << (on ? num(on->tracker_ms.mean, 1) + " / " + num(on->tracker_ms.median, 1) : "n/a") << " |\n";
  md << "| segmentation mean / median [ms] (own thread) | "
     << (off ? num(off->segmentation_ms.mean, 1) + " / " + num(off->segmentation_ms.median, 1) : "n/a") << " | "
     << (on ? num(on->segmentation_ms.mean, 1) + " / " + num(on->segmentation_ms.median, 1) : "n/a") << " |\n";
  md << "| waiting for the mask mean [ms] | "
     << cell(off, [](const RunRecord& r) { return r.segmentation_wait_ms.mean; }, 1) << " | "
     << cell(on, [](const RunRecord& r) { return r.segmentation_wait_ms.mean; }, 1) << " |\n";
  md << "| frames tracked | " << tracked_cell(s.off) << " | " << tracked_cell(s.on) << " |\n";
  md << "| tracking loss (frames lost / episodes) | " << lost_cell(s.off) << " | " << lost_cell(s.on) << " |\n";
  md << "| keyframes | " << (off ? std::to_string(off->keyframes) : "n/a") << " | "
     << (on ? std::to_string(on->keyframes) : "n/a") << " |\n";
  md << "| wall time of the run [s] | " << cell(off, [](const RunRecord& r) { return r.wall_seconds; }, 1) << " | "
     << cell(on, [](const RunRecord& r) { return r.wall_seconds; }, 1) << " |\n";
  const auto ba_ms = [](const RunRecord* r) {
    return r ? num(r->local_ba.cpu_ms.median, 1) + " / " + num(r->local_ba.cpu_ms.p95, 1) : std::string("n/a");
  };
  const auto ba_aborted = [](const RunRecord* r) {
    return r ? std::to_string(r->local_ba.aborted) + " / " + std::to_string(r->local_ba.runs) + " (" +
                   num(100 * r->local_ba.aborted_share, 0) + " %; tracking " +
                   std::to_string(r->local_ba.aborted_by_tracking) + ", pause " +
                   std::to_string(r->local_ba.aborted_by_pause) + "; cut short " +
                   std::to_string(r->local_ba.cut_short) + ", discarded " +
                   std::to_string(r->local_ba.discarded) + ", " + num(100 * r->local_ba.discarded_share, 0) + " %)"
             : std::string("n/a");
  };
  const auto ba_window = [](const RunRecord* r) {
    return r ? num(r->local_ba.keyframes.median, 0) + " + " + num(r->local_ba.fixed_keyframes.median, 0) + " / " +
                   num(r->local_ba.points.median, 0) + " / " + num(r->local_ba.observations.median, 0)
             : std::string("n/a");
  };
  md << "| local BA CPU median / p95 [ms] | " << ba_ms(off) << " | " << ba_ms(on) << " |\n";
  md << "| local BAs aborted / run | " << ba_aborted(off) << " | " << ba_aborted(on) << " |\n";
  md << "| local BA window median (keyframes + fixed / points / observations) | " << ba_window(off) << " | "
     << ba_window(on) << " |\n";
  md << "| mapping CPU per frame [ms] | "
     << cell(off, [](const RunRecord& r) { return r.local_ba.mapping_cpu_ms_per_frame; }, 1) << " | "
     << cell(on, [](const RunRecord& r) { return r.local_ba.mapping_cpu_ms_per_frame; }, 1) << " |\n";
  md << "| keyframes mapped per second of input | "
     << cell(off, [](const RunRecord& r) { return r.local_ba.keyframes_per_second; }, 1) << " | "
     << cell(on, [](const RunRecord& r) { return r.local_ba.keyframes_per_second; }, 1) << " |\n";
}

void runs_table(std::ostringstream& md, const SequenceResult& s, const fs::path& report_dir) {
  md << "| mode | run | ATE rmse [m] | RPE trans 1 s rmse [m] | tracked | lost (frames/episodes) | ms/frame | "
        "status | trajectory |\n|---|---:|---:|---:|---:|---:|---:|---|---|\n";
  for (const ModeResult* m : {&s.off, &s.on}) {
    for (std::size_t k = 0; k < m->runs.size(); ++k) {
      const RunRecord& r = m->runs[k];
      std::string status = r.error ? "failed: " + *r.error
                           : !r.accuracy ? "not evaluated: " + r.evaluation_error.value_or("?")
                                         : "ok";
      if (m->median && *m->median == k) status += " (median)";
      for (char& c : status) {
        if (c == '|' || c == '\n') c = ' ';
      }
      std::string link = "-";
      if (!r.trajectory_file.empty()) {
        const std::string rel = r.trajectory_file.lexically_relative(report_dir).generic_string();
        link = "[trajectory.txt](" + (rel.empty() ? r.trajectory_file.generic_string() : rel) + ")";
      }
      md << "| " << (m->segmentation ? "on" : "off") << " | " << r.run << " | "
         << (r.accuracy ? num(r.accuracy->ape.rmse, 4) : "n/a") << " | "
         << (r.accuracy ? num(r.accuracy->rpe_trans_1s.rmse, 4) : "n/a") << " | " << r.tracked << "/" << r.frames
         << " | " << r.lost_frames << "/" << r.lost_episodes << " | " << num(r.frames ? r.total_ms.mean : kNaN, 1)
         << " | " << status << " | " << link << " |\n";
    }
  }
}

}  // namespace

std::string benchmark_summary_table(const std::vector<SequenceResult>& results) {
  std::ostringstream md;
  md << "| sequence | ATE rmse off [m] | ATE rmse on [m] | ATE impr. | RPE 1 s off [m/s] | RPE 1 s on [m/s] | "
        "RPE impr. | RPE rot 1 s off [deg/s] | RPE rot 1 s on [deg/s] | rot impr. | ms/frame off | ms/frame on | "
        "tracked off | tracked on | lost off | lost on |\n";
  md << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const SequenceResult& s : results) {
    if (s.error) {
      md << "| " << s.input.name << " | failed: " << s.error->substr(0, 80)
         << " |  |  |  |  |  |  |  |  |  |  |  |  |  |  |\n";
      continue;
    }
    const auto ape = [](const AccuracyStats& a) { return a.ape.rmse; };
    const auto rpe = [](const AccuracyStats& a) { return a.rpe_trans_1s.rmse; };
    const auto rot = [](const AccuracyStats& a) { return a.rpe_rot_1s.rmse; };
    md << "| " << s.input.name << " | " << num(stat(s.off, ape), 4) << failed_note(s.off) << " | "
       << num(stat(s.on, ape), 4) << failed_note(s.on) << " | "
       << pct(improvement_percent(stat(s.off, ape), stat(s.on, ape))) << " | " << num(stat(s.off, rpe), 4) << " | "
       << num(stat(s.on, rpe), 4) << " | " << pct(improvement_percent(stat(s.off, rpe), stat(s.on, rpe))) << " | "
       << num(stat(s.off, rot), 3) << " | " << num(stat(s.on, rot), 3) << " | "
       << pct(improvement_percent(stat(s.off, rot), stat(s.on, rot))) << " | " << num(time_of(s.off), 1) << " | "
       << num(time_of(s.on), 1) << " | " << tracked_cell(s.off) << " | " << tracked_cell(s.on) << " | "
       << lost_cell(s.off) << " | " << lost_cell(s.on) << " |\n";
  }
  return md.str();
}

std::string benchmark_markdown(const std::vector<SequenceResult>& results, const BenchmarkOptions& options,
                               const std::vector<SequencePlots>& plots) {
  std::ostringstream md;
  md << "# stillslam benchmark: segmentation off (baseline) vs on (ours)\n\n";
  md << "Each sequence was run " << options.runs << " time(s) per mode on identical settings"
     << (options.deterministic ? " (deterministic local mapping)" : "") << ", in-process, without realtime pacing"
     << (options.max_frames ? ", at most " + std::to_string(*options.max_frames) + " frames" : "")
     << ". The baseline is the same pipeline without the dynamic-object masks. Every number below is from the "
        "median run of its mode (by APE rmse; failed runs rank last). Improvement = (off - on) / off.\n\n";
  md << "- **APE**: translation error after SE3 (Horn) alignment, TUM greedy timestamp association (0.02 s).\n";
  md << "- **RPE per frame**: consecutive 1-frame steps. **RPE per second**: every pose against the pose 1 s "
        "later (TUM `evaluate_rpe.py --fixed_delta --delta 1 --delta_unit s`), the drift the DynaSLAM-style "
        "tables report in m/s and deg/s.\n";
  md << "- **Time per frame**: frame building (ORB extraction, waiting for the mask, depth/stereo association) "
        "plus tracking, on the tracking thread. Segmentation runs on its own thread in parallel with ORB "
        "extraction; its own time is listed separately.\n";
  md << "- **Lost**: frames in the Lost state / separate lost episodes.\n\n";
  md << "## Summary (median runs)\n\n" << benchmark_summary_table(results) << "\n";
  for (std::size_t i = 0; i < results.size(); ++i) {
    const SequenceResult& s = results[i];
    md << "## " << s.input.name << "\n\n";
    md << "- folder: `" << s.input.folder.string() << "`\n- settings: `" << s.input.config.string()
       << "`\n- ground truth: `" << s.input.groundtruth.string() << "`\n";
    if (s.error) {
      md << "\n**Not benchmarked:** " << *s.error << "\n\n";
      continue;
    }
    md << "- dataset: " << s.dataset_kind << " (" << s.sensor << "), " << s.dataset_frames << " frames, "
       << s.groundtruth.size() << " ground-truth poses\n";
    if (!s.on.segmentation_active) {
      md << "- **note:** segmentation did not run in the \"on\" mode (Segmentation.enabled is false in the "
            "settings), so both modes are the baseline\n";
    }
    const RunRecord* off = s.off.median_run();
    const RunRecord* on = s.on.median_run();
    md << "- median runs: off run " << (off ? std::to_string(off->run) : "n/a") << failed_note(s.off)
       << ", on run " << (on ? std::to_string(on->run) : "n/a") << failed_note(s.on) << "\n\n";
    md << "### Accuracy\n\n";
    accuracy_table(md, s);
    md << "\n### Time and tracking\n\n";
    timing_table(md, s);
    md << "\n### All runs\n\n";
    runs_table(md, s, options.output_dir);
    if (i < plots.size() && !plots[i].trajectories.empty()) {
      md << "\n### Plots\n\n";
      md << "![trajectories](" << plots[i].trajectories.generic_string() << ")\n\n";
      md << "![APE over time](" << plots[i].ape.generic_string() << ")\n\n";
      md << "![RPE over time](" << plots[i].rpe.generic_string() << ")\n\n";
      md << "[trajectories](" << plots[i].trajectories.generic_string() << ") · [APE](" << plots[i].ape.generic_string()
         << ") · [RPE](" << plots[i].rpe.generic_string() << ")\n";
    }
    md << "\n";
  }
  return md.str();
}

}  // namespace stillslam
