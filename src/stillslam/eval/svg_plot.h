#pragma once
// Minimal hand-written SVG line plots (no plotting dependency): axes with
// ticks, polylines, a legend. Enough for trajectory and error plots.
#include <string>
#include <vector>

namespace stillslam {

struct PlotSeries {
  std::string label;
  std::string color;  // any SVG colour, e.g. "#1f77b4"
  std::vector<double> x;
  std::vector<double> y;
  bool dashed = false;
};

struct PlotOptions {
  std::string title;
  std::string x_label;
  std::string y_label;
  int width = 800;
  int height = 600;
  bool equal_axes = false;  // same metres per pixel on both axes (trajectory views)
};

// A self-contained SVG document. A non-finite point breaks a series into
// separate polylines (no line is drawn across it).
std::string render_line_plot(const std::vector<PlotSeries>& series, const PlotOptions& options);

}  // namespace stillslam
