// SVG figures of the HTML run report (run_report_parts.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "stillslam/benchmark/html_text.h"
#include "stillslam/benchmark/plot_geometry.h"
#include "stillslam/benchmark/run_report_parts.h"
#include "stillslam/eval/svg_plot.h"

namespace stillslam {
namespace {

constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

double frame_number(const nlohmann::json& frame, const char* key) {
  const auto it = frame.find(key);
  return it != frame.end() && it->is_number() ? it->get<double>() : 0.0;
}

double frame_time(const nlohmann::json& frame, const char* stage) {
  const auto times = frame.find("times_ms");
  return times == frame.end() ? 0.0 : frame_number(*times, stage);
}

// A series over stamps with a break (NaN) where the stamps jump (tracking lost).
PlotSeries broken_series(const std::string& label, const std::string& color, const std::vector<double>& t,
                         const std::vector<double>& v, double t0) {
  PlotSeries s{label, color, {}, {}, false};
  const double limit = stamp_gap_limit(t);
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (k > 0 && t[k] - t[k - 1] > limit) {
      s.x.push_back(kNoValue);
      s.y.push_back(kNoValue);
    }
    s.x.push_back(t[k] - t0);
    s.y.push_back(v[k]);
  }
  return s;
}

// Time axis origin: the first evaluated ground-truth stamp of any run.
double first_evaluated_stamp(const std::vector<ReportRun>& runs) {
  double t0 = std::numeric_limits<double>::infinity();
  for (const ReportRun& r : runs) {
    if (r.evaluation && !r.evaluation->gt.empty()) t0 = std::min(t0, r.evaluation->gt.front().timestamp);
  }
  return std::isfinite(t0) ? t0 : 0.0;
}

std::vector<double> frame_indices(const ReportRun& run) {
  std::vector<double> x;
  for (const nlohmann::json& f : run.stats["frames"]) x.push_back(frame_number(f, "index"));
  return x;
}

}  // namespace

std::string report_run_color(std::size_t k) {
  constexpr std::array<const char*, 6> kPalette{"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf"};
  return kPalette[k % kPalette.size()];
}

std::string report_trajectory_svg(const std::vector<ReportRun>& runs, const Trajectory& groundtruth) {
  Trajectory reference = groundtruth;
  if (reference.empty() && !runs.empty()) reference = runs.front().trajectory;
  const std::array<int, 2> axes = spread_axes(reference);
  const std::array<const char*, 3> names{"x [m]", "y [m]", "z [m]"};
  // Ground truth over the span the runs cover.
  double t_begin = std::numeric_limits<double>::infinity(), t_end = -t_begin;
  for (const ReportRun& r : runs) {
    if (!r.evaluation || r.evaluation->gt.empty()) continue;
    t_begin = std::min(t_begin, r.evaluation->gt.front().timestamp);
    t_end = std::max(t_end, r.evaluation->gt.back().timestamp);
  }
  std::vector<PlotSeries> series;
  if (!groundtruth.empty()) {
    PlotSeries gt{"ground truth", kReportGroundTruthColor, {}, {}, true};
    for (const StampedPose& p : groundtruth) {
      if (std::isfinite(t_begin) && (p.timestamp < t_begin || p.timestamp > t_end)) continue;
      gt.x.push_back(p.T_world_cam.translation()[axes[0]]);
      gt.y.push_back(p.T_world_cam.translation()[axes[1]]);
    }
    series.push_back(std::move(gt));
  }
  for (std::size_t k = 0; k < runs.size(); ++k) {
    // Aligned when evaluated, else as estimated.
    const Trajectory& poses = runs[k].evaluation ? runs[k].evaluation->est_aligned : runs[k].trajectory;
    std::vector<double> t;
    for (const StampedPose& p : poses) t.push_back(p.timestamp);
    const double limit = stamp_gap_limit(t);
    PlotSeries s{runs[k].label, report_run_color(k), {}, {}, false};
    for (std::size_t i = 0; i < poses.size(); ++i) {
      if (i > 0 && t[i] - t[i - 1] > limit) {  // no line across a stretch of lost frames
        s.x.push_back(kNoValue);
        s.y.push_back(kNoValue);
      }
      s.x.push_back(poses[i].T_world_cam.translation()[axes[0]]);
      s.y.push_back(poses[i].T_world_cam.translation()[axes[1]]);
    }
    series.push_back(std::move(s));
  }
  PlotOptions options;
  options.title = groundtruth.empty() ? "trajectory from above (no ground truth)"
                                      : "trajectories from above (SE3 aligned) against ground truth";
  options.x_label = names[axes[0]];
  options.y_label = names[axes[1]];
  options.equal_axes = true;
  return inline_svg(render_line_plot(series, options));
}

std::string report_ape_svg(const std::vector<ReportRun>& runs) {
  const double t0 = first_evaluated_stamp(runs);
  std::vector<PlotSeries> series;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (!runs[k].evaluation) continue;
    const EvaluationResult& ev = *runs[k].evaluation;
    std::vector<double> t;
    for (const StampedPose& p : ev.gt) t.push_back(p.timestamp);
    char label[200];
    std::snprintf(label, sizeof(label), "%s, rmse %.4f m", runs[k].label.c_str(), ev.ape_stats.rmse);
    series.push_back(broken_series(label, report_run_color(k), t, ev.ape, t0));
  }
  PlotOptions options;
  options.title = "absolute position error over time";
  options.x_label = "time since first pose [s]";
  options.y_label = "APE [m]";
  options.height = 360;
  return inline_svg(render_line_plot(series, options));
}

std::string report_rpe_svg(const std::vector<ReportRun>& runs) {
  const double t0 = first_evaluated_stamp(runs);
  std::vector<PlotSeries> series;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (!runs[k].evaluation) continue;
    const EvaluationResult& ev = *runs[k].evaluation;
    std::vector<double> t, e;
    for (std::size_t i = 0; i < ev.rpe_pairs.size() && i < ev.rpe.translation.size(); ++i) {
      t.push_back(ev.gt[ev.rpe_pairs[i].first].timestamp);
      e.push_back(ev.rpe.translation[i]);
    }
    series.push_back(broken_series(runs[k].label, report_run_color(k), t, e, t0));
  }
  PlotOptions options;
  options.title = "translational RPE per frame over time";
  options.x_label = "time since first pose [s]";
  options.y_label = "RPE [m]";
  options.height = 360;
  return inline_svg(render_line_plot(series, options));
}

std::string report_timing_svg(const ReportRun& run) {
  // Stages of the tracking thread, stacked: each line is the sum of the
  // stages up to it; the top one is the frame's total.
  struct Stage {
    const char* key;
    const char* label;
    const char* color;
  };
  constexpr std::array<Stage, 5> kStages{{{"extraction", "ORB extraction", "#1f77b4"},
                                          {"segmentation_wait", "+ waiting for the mask", "#ff7f0e"},
                                          {"association", "+ stereo / depth association", "#2ca02c"},
                                          {"tracking", "+ tracking", "#9467bd"},
                                          {"mapping_inline", "+ local mapping (deterministic)", "#8c564b"}}};
  const std::vector<double> x = frame_indices(run);
  std::vector<double> sum(x.size(), 0.0);
  std::vector<PlotSeries> series;
  for (const Stage& stage : kStages) {
    PlotSeries s{stage.label, stage.color, x, {}, false};
    for (std::size_t i = 0; i < x.size(); ++i) {
      sum[i] += frame_time(run.stats["frames"][i], stage.key);
      s.y.push_back(sum[i]);
    }
    series.push_back(std::move(s));
  }
  PlotSeries total{"total (incl. frame building rest)", "#000000", x, {}, true};
  for (const nlohmann::json& f : run.stats["frames"]) total.y.push_back(frame_time(f, "total"));
  series.push_back(std::move(total));
  PlotOptions options;
  options.title = "time per frame, stacked by stage (tracking thread)";
  options.x_label = "frame";
  options.y_label = "ms";
  options.height = 360;
  return inline_svg(render_line_plot(series, options));
}

std::string report_features_svg(const ReportRun& run) {
  const std::vector<double> x = frame_indices(run);
  PlotSeries kept{"kept", "#2ca02c", x, {}, false};
  PlotSeries removed{"removed by the dynamic mask", "#d62728", x, {}, false};
  for (const nlohmann::json& f : run.stats["frames"]) {
    const double after = frame_number(f, "features_after_filter");
    kept.y.push_back(after);
    // `run` records what the mask removed; older stats only the filter's own count.
    removed.y.push_back(f.contains("features_removed") ? frame_number(f, "features_removed")
                                                       : frame_number(f, "features_before_filter") - after);
  }
  PlotOptions options;
  options.title = "features per frame";
  options.x_label = "frame";
  options.y_label = "features";
  options.height = 320;
  return inline_svg(render_line_plot({kept, removed}, options));
}

std::string report_mask_svg(const ReportRun& run) {
  const std::vector<double> x = frame_indices(run);
  PlotSeries coverage{"dynamic mask", "#e377c2", x, {}, false};
  PlotSeries held{"of which held over (MaskHold)", "#7f7f7f", x, {}, true};
  for (const nlohmann::json& f : run.stats["frames"]) {
    coverage.y.push_back(100.0 * frame_number(f, "mask_coverage"));
    held.y.push_back(100.0 * frame_number(f, "held_mask_coverage"));
  }
  PlotOptions options;
  options.title = "mask coverage per frame";
  options.x_label = "frame";
  options.y_label = "% of the image";
  options.height = 320;
  return inline_svg(render_line_plot({coverage, held}, options));
}

std::string report_state_timeline_svg(const ReportRun& run) {
  const nlohmann::json& frames = run.stats["frames"];
  const std::size_t n = frames.size();
  constexpr double kWidth = 800, kLeft = 10, kBar = 24, kTop = 8;
  const double step = n > 0 ? (kWidth - 2 * kLeft) / static_cast<double>(n) : 0;
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"timeline\" width=\"800\" height=\"74\">";
  char buf[320];
  for (std::size_t i = 0; i < n; ++i) {
    const std::string state = frames[i].value("state", "");
    const std::string reason = frames[i].value("reason", "");
    const char* color = state == "ok" ? "#2ca02c" : state == "lost" ? "#d62728" : "#bbbbbb";
    std::snprintf(buf, sizeof(buf), "<rect x=\"%.2f\" y=\"%.0f\" width=\"%.2f\" height=\"%.0f\" fill=\"%s\">",
                  kLeft + step * static_cast<double>(i), kTop, std::max(step, 0.5), kBar, color);
    svg += buf;
    svg += "<title>frame " + std::to_string(frames[i].value("index", 0)) + ": " + html_escape(state) + ", " +
           html_escape(reason) + "</title></rect>";
    const double cx = kLeft + step * (static_cast<double>(i) + 0.5);
    if (reason == "relocalized") {
      std::snprintf(buf, sizeof(buf),
                    "<path class=\"relocalized\" d=\"M%.2f %.0f l-5 10 h10 z\" fill=\"#1f77b4\"/>", cx,
                    kTop + kBar + 2);
      svg += buf;
    }
    if (frames[i].value("keyframe", false)) {
      std::snprintf(buf, sizeof(buf), "<line x1=\"%.2f\" x2=\"%.2f\" y1=\"%.0f\" y2=\"%.0f\" stroke=\"#000\"/>", cx,
                    cx, kTop - 6, kTop);
      svg += buf;
    }
  }
  std::snprintf(buf, sizeof(buf),
                "<text x=\"%.0f\" y=\"68\" font-size=\"11\" font-family=\"sans-serif\">green ok, red lost, gray "
                "not initialized; blue triangle: relocalized; tick above: keyframe</text>",
                kLeft);
  svg += buf;
  return svg + "</svg>";
}

}  // namespace stillslam
