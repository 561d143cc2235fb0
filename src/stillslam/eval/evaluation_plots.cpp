#include "stillslam/eval/evaluation_plots.h"

#include <array>
#include <fstream>

#include "stillslam/core/error.h"
#include "stillslam/eval/svg_plot.h"

namespace stillslam {
namespace {

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.flush();
  if (!out) throw Error("cannot write plot " + path.string() + "; check that its folder exists and is writable");
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
  for (const StampedPose& p : result.gt) {
    gt.x.push_back(p.T_world_cam.translation()[axes[0]]);
    gt.y.push_back(p.T_world_cam.translation()[axes[1]]);
  }
  for (const StampedPose& p : result.est_aligned) {
    est.x.push_back(p.T_world_cam.translation()[axes[0]]);
    est.y.push_back(p.T_world_cam.translation()[axes[1]]);
  }
  PlotOptions options;
  options.title = "trajectory (" + std::to_string(result.pairs) + " associated poses)";
  options.x_label = names[axes[0]];
  options.y_label = names[axes[1]];
  options.equal_axes = true;
  return render_line_plot({gt, est}, options);
}

std::string ape_over_time_svg(const EvaluationResult& result) {
  PlotSeries ape{"APE", "#d62728", {}, result.ape, false};
  const double t0 = result.gt.empty() ? 0.0 : result.gt.front().timestamp;
  for (const StampedPose& p : result.gt) ape.x.push_back(p.timestamp - t0);
  PlotSeries rmse{"rmse", "#444444", {}, {}, true};
  if (!ape.x.empty()) {
    rmse.x = {ape.x.front(), ape.x.back()};
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
  write_text(path, trajectory_view_svg(result));
  write_text(error_path, ape_over_time_svg(result));
  return error_path;
}

}  // namespace stillslam
