#include "stillslam/eval/evaluation_plots.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <limits>
#include <vector>
#include <fstream>

#include "stillslam/core/error.h"
#include "stillslam/core/text_file.h"
#include "stillslam/eval/svg_plot.h"

namespace stillslam {
namespace {

// Indices k where the associated sequence has a hole before pose k (tracking
// lost or poses missing): more than ten times the median step and 0.5 s.
std::vector<bool> gap_before(const Trajectory& poses) {
  std::vector<bool> gaps(poses.size(), false);
  if (poses.size() < 3) return gaps;
  std::vector<double> steps;
  for (std::size_t k = 1; k < poses.size(); ++k) steps.push_back(poses[k].timestamp - poses[k - 1].timestamp);
  std::vector<double> sorted(steps);
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
  const double limit = std::max(10.0 * sorted[sorted.size() / 2], 0.5);
  for (std::size_t k = 1; k < poses.size(); ++k) gaps[k] = steps[k - 1] > limit;
  return gaps;
}

void add_point(PlotSeries& series, bool gap, double x, double y) {
  if (gap) {
    series.x.push_back(std::numeric_limits<double>::quiet_NaN());
    series.y.push_back(std::numeric_limits<double>::quiet_NaN());
  }
  series.x.push_back(x);
  series.y.push_back(y);
}

}  // namespace

std::string trajectory_view_svg(const EvaluationResult& result) {
  // Drop the axis with the least ground-truth variance.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const StampedPose& p : result.gt) mean += p.T_world_cam.translation();
  mean /= std::max<std::size_t>(result.gt.size(), 1);
  Eigen::Vector3d variance = Eigen::Vector3d::Zero();
  for (const StampedPose& p : result.gt) variance += (p.T_world_cam.translation() - mean).cwiseAbs2();
  int dropped = 0;
  variance.minCoeff(&dropped);
  std::array<int, 2> axes{};
  for (int a = 0, k = 0; a < 3; ++a) {
    if (a != dropped) axes[k++] = a;
  }
  const std::array<const char*, 3> names{"x [m]", "y [m]", "z [m]"};

  PlotSeries gt{"ground truth", "#444444", {}, {}, true};
  PlotSeries est{"estimate (" + to_string(result.alignment.type) + " aligned)", "#1f77b4", {}, {}, false};
  const std::vector<bool> gaps = gap_before(result.gt);
  for (std::size_t k = 0; k < result.gt.size(); ++k) {
    const Eigen::Vector3d g = result.gt[k].T_world_cam.translation();
    const Eigen::Vector3d e = result.est_aligned[k].T_world_cam.translation();
    add_point(gt, gaps[k], g[axes[0]], g[axes[1]]);
    add_point(est, gaps[k], e[axes[0]], e[axes[1]]);
  }
  PlotOptions options;
  options.title = "trajectory (" + std::to_string(result.pairs) + " associated poses)";
  options.x_label = names[axes[0]];
  options.y_label = names[axes[1]];
  options.equal_axes = true;
  return render_line_plot({gt, est}, options);
}

std::string ape_over_time_svg(const EvaluationResult& result) {
  PlotSeries ape{"APE", "#d62728", {}, {}, false};
  const double t0 = result.gt.empty() ? 0.0 : result.gt.front().timestamp;
  const std::vector<bool> gaps = gap_before(result.gt);
  for (std::size_t k = 0; k < result.gt.size(); ++k) add_point(ape, gaps[k], result.gt[k].timestamp - t0, result.ape[k]);
  PlotSeries rmse{"rmse", "#444444", {}, {}, true};
  if (!result.gt.empty()) {
    rmse.x = {0.0, result.gt.back().timestamp - t0};
    rmse.y = {result.ape_stats.rmse, result.ape_stats.rmse};
  }
  char title[128];
  std::snprintf(title, sizeof(title), "absolute position error (rmse %.4f m, max %.4f m)", result.ape_stats.rmse,
                result.ape_stats.max);
  PlotOptions options;
  options.title = title;
  options.x_label = "time since first pose [s]";
  options.y_label = "APE [m]";
  options.height = 400;
  return render_line_plot({ape, rmse}, options);
}

std::filesystem::path write_evaluation_plots(const std::filesystem::path& path, const EvaluationResult& result) {
  std::filesystem::path error_path = path;
  error_path.replace_filename(path.stem().string() + "_error" + (path.has_extension() ? path.extension().string() : ".svg"));
  write_text_file(path, trajectory_view_svg(result));
  write_text_file(error_path, ape_over_time_svg(result));
  return error_path;
}

}  // namespace stillslam
