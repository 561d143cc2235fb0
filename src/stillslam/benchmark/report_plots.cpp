// Per-sequence figures of the benchmark report (part of report.h).
#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <limits>

#include "stillslam/core/error.h"
#include "stillslam/core/text_file.h"
#include "stillslam/eval/metrics.h"
#include "stillslam/eval/svg_plot.h"
#include "stillslam/benchmark/plot_geometry.h"
#include "stillslam/benchmark/report.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

constexpr const char* kOffColor = "#d62728";  // baseline
constexpr const char* kOnColor = "#1f77b4";   // ours
constexpr const char* kGtColor = "#444444";

struct ModeCurve {
  std::string label, color;
  EvaluationResult eval;
  std::vector<double> rpe_t, rpe_err;  // start time since t0, error
};

void push(PlotSeries& s, bool gap, double x, double y) {
  if (gap) {
    s.x.push_back(std::numeric_limits<double>::quiet_NaN());
    s.y.push_back(std::numeric_limits<double>::quiet_NaN());
  }
  s.x.push_back(x);
  s.y.push_back(y);
}

PlotSeries stamped_series(const std::string& label, const std::string& color, const std::vector<double>& t,
                          const std::vector<double>& v, double t0) {
  PlotSeries s{label, color, {}, {}, false};
  const double limit = stamp_gap_limit(t);
  for (std::size_t k = 0; k < t.size(); ++k) push(s, k > 0 && t[k] - t[k - 1] > limit, t[k] - t0, v[k]);
  return s;
}

std::vector<ModeCurve> mode_curves(const SequenceResult& result) {
  std::vector<ModeCurve> curves;
  for (const ModeResult* mode : {&result.off, &result.on}) {
    const RunRecord* run = mode->median_run();
    if (run == nullptr || !run->accuracy) continue;
    ModeCurve c;
    c.label = std::string(mode->segmentation ? "segmentation on" : "segmentation off") + " (run " +
              std::to_string(run->run) + ")";
    c.color = mode->segmentation ? kOnColor : kOffColor;
    try {
      c.eval = evaluate(result.groundtruth, run->trajectory, benchmark_ape_options());
    } catch (const Error&) {
      continue;
    }
    std::vector<PosePair> pairs = select_pose_pairs(c.eval.gt, rpe_per_second_pairs());
    if (pairs.empty()) pairs = c.eval.rpe_pairs;
    const RelativeErrors rel = relative_errors(c.eval.gt, c.eval.est_aligned, pairs);
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      c.rpe_t.push_back(c.eval.gt[pairs[k].first].timestamp);
      c.rpe_err.push_back(rel.translation[k]);
    }
    curves.push_back(std::move(c));
  }
  return curves;
}

std::string trajectories_svg(const SequenceResult& result, const std::vector<ModeCurve>& curves) {
  const std::array<int, 2> axes = spread_axes(result.groundtruth);
  const std::array<const char*, 3> names{"x [m]", "y [m]", "z [m]"};
  std::vector<PlotSeries> series;
  // Ground truth over the span the runs cover (the whole file may be longer
  // than --max-frames allowed).
  double t_begin = std::numeric_limits<double>::infinity(), t_end = -t_begin;
  for (const ModeCurve& c : curves) {
    t_begin = std::min(t_begin, c.eval.gt.front().timestamp);
    t_end = std::max(t_end, c.eval.gt.back().timestamp);
  }
  PlotSeries gt{"ground truth", kGtColor, {}, {}, true};
  for (const StampedPose& p : result.groundtruth) {
    if (!curves.empty() && (p.timestamp < t_begin || p.timestamp > t_end)) continue;
    gt.x.push_back(p.T_world_cam.translation()[axes[0]]);
    gt.y.push_back(p.T_world_cam.translation()[axes[1]]);
  }
  series.push_back(std::move(gt));
  for (const ModeCurve& c : curves) {
    std::vector<double> t, x, y;
    for (const StampedPose& p : c.eval.est_aligned) {
      t.push_back(p.timestamp);
      x.push_back(p.T_world_cam.translation()[axes[0]]);
      y.push_back(p.T_world_cam.translation()[axes[1]]);
    }
    PlotSeries s{c.label, c.color, {}, {}, false};
    const double limit = stamp_gap_limit(t);
    for (std::size_t k = 0; k < t.size(); ++k) push(s, k > 0 && t[k] - t[k - 1] > limit, x[k], y[k]);
    series.push_back(std::move(s));
  }
  PlotOptions options;
  options.title = result.input.name + ": trajectories (SE3 aligned) against ground truth";
  options.x_label = names[axes[0]];
  options.y_label = names[axes[1]];
  options.equal_axes = true;
  return render_line_plot(series, options);
}

std::string ape_svg(const SequenceResult& result, const std::vector<ModeCurve>& curves, double t0) {
  std::vector<PlotSeries> series;
  for (const ModeCurve& c : curves) {
    std::vector<double> t;
    for (const StampedPose& p : c.eval.gt) t.push_back(p.timestamp);
    char label[160];
    std::snprintf(label, sizeof(label), "%s, rmse %.4f m", c.label.c_str(), c.eval.ape_stats.rmse);
    series.push_back(stamped_series(label, c.color, t, c.eval.ape, t0));
  }
  PlotOptions options;
  options.title = result.input.name + ": absolute position error over time";
  options.x_label = "time since first pose [s]";
  options.y_label = "APE [m]";
  options.height = 400;
  return render_line_plot(series, options);
}

std::string rpe_svg(const SequenceResult& result, const std::vector<ModeCurve>& curves, double t0) {
  std::vector<PlotSeries> series;
  for (const ModeCurve& c : curves) series.push_back(stamped_series(c.label, c.color, c.rpe_t, c.rpe_err, t0));
  PlotOptions options;
  options.title = result.input.name + ": translational RPE over 1 s (per frame if shorter)";
  options.x_label = "start of the interval since first pose [s]";
  options.y_label = "RPE [m]";
  options.height = 400;
  return render_line_plot(series, options);
}

}  // namespace

SequencePlots write_sequence_plots(const fs::path& dir, const SequenceResult& result) {
  const std::vector<ModeCurve> curves = mode_curves(result);
  // Time axis from the first evaluated pose of either mode.
  double t0 = result.groundtruth.empty() ? 0.0 : result.groundtruth.front().timestamp;
  if (!curves.empty()) {
    t0 = curves.front().eval.gt.front().timestamp;
    for (const ModeCurve& c : curves) t0 = std::min(t0, c.eval.gt.front().timestamp);
  }
  SequencePlots plots;
  plots.trajectories = result.input.name + "_trajectories.svg";
  plots.ape = result.input.name + "_ape.svg";
  plots.rpe = result.input.name + "_rpe.svg";
  write_text_file(dir / plots.trajectories, trajectories_svg(result, curves));
  write_text_file(dir / plots.ape, ape_svg(result, curves, t0));
  write_text_file(dir / plots.rpe, rpe_svg(result, curves, t0));
  return plots;
}

}  // namespace stillslam
