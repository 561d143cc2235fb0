#include "stillslam/eval/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "stillslam/core/text.h"

namespace stillslam {
namespace {

constexpr double kLeft = 80, kRight = 20, kTop = 40, kBottom = 60;

std::string num(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.2f", v);
  return buffer;
}

std::string tick_label(double v, double step) {
  char buffer[32];
  const int decimals = std::clamp(static_cast<int>(std::ceil(-std::log10(step))), 0, 9);
  std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, std::abs(v) < step * 1e-6 ? 0.0 : v);
  return buffer;
}

// 1, 2 or 5 times a power of ten, giving about `target` intervals.
double nice_step(double range, int target) {
  const double raw = range / target;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double fraction = raw / magnitude;
  const double nice = fraction < 1.5 ? 1 : fraction < 3.5 ? 2 : fraction < 7.5 ? 5 : 10;
  return nice * magnitude;
}

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool valid() const { return lo <= hi; }
  void pad() {
    if (!valid()) {
      lo = 0;
      hi = 1;
    }
    if (hi - lo < 1e-12) {
      lo -= 0.5;
      hi += 0.5;
    }
    const double margin = 0.03 * (hi - lo);
    lo -= margin;
    hi += margin;
  }
};

}  // namespace

std::string render_line_plot(const std::vector<PlotSeries>& series, const PlotOptions& options) {
  Range xr, yr;
  for (const PlotSeries& s : series) {
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      xr.add(s.x[i]);
      yr.add(s.y[i]);
    }
  }
  xr.pad();
  yr.pad();
  const double plot_w = options.width - kLeft - kRight;
  const double plot_h = options.height - kTop - kBottom;
  if (options.equal_axes) {
    // Grow the tighter axis so one metre spans the same pixels on both.
    const double per_px = std::max((xr.hi - xr.lo) / plot_w, (yr.hi - yr.lo) / plot_h);
    const double xc = 0.5 * (xr.lo + xr.hi), yc = 0.5 * (yr.lo + yr.hi);
    xr.lo = xc - 0.5 * per_px * plot_w;
    xr.hi = xc + 0.5 * per_px * plot_w;
    yr.lo = yc - 0.5 * per_px * plot_h;
    yr.hi = yc + 0.5 * per_px * plot_h;
  }
  auto px = [&](double x) { return kLeft + (x - xr.lo) / (xr.hi - xr.lo) * plot_w; };
  auto py = [&](double y) { return kTop + (yr.hi - y) / (yr.hi - yr.lo) * plot_h; };

  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(options.width) +
                    "\" height=\"" + std::to_string(options.height) + "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg += "<text x=\"" + num(options.width / 2.0) + "\" y=\"24\" text-anchor=\"middle\" font-size=\"16\">" +
         html_escape(options.title) + "</text>\n";
  svg += "<rect x=\"" + num(kLeft) + "\" y=\"" + num(kTop) + "\" width=\"" + num(plot_w) + "\" height=\"" +
         num(plot_h) + "\" fill=\"none\" stroke=\"black\"/>\n";

  const double xs = nice_step(xr.hi - xr.lo, 8);
  for (double v = std::ceil(xr.lo / xs) * xs; v <= xr.hi; v += xs) {
    svg += "<line x1=\"" + num(px(v)) + "\" y1=\"" + num(kTop) + "\" x2=\"" + num(px(v)) + "\" y2=\"" +
           num(kTop + plot_h) + "\" stroke=\"#e0e0e0\"/>\n";
    svg += "<text x=\"" + num(px(v)) + "\" y=\"" + num(kTop + plot_h + 16) + "\" text-anchor=\"middle\">" +
           tick_label(v, xs) + "</text>\n";
  }
  const double ys = nice_step(yr.hi - yr.lo, 8);
  for (double v = std::ceil(yr.lo / ys) * ys; v <= yr.hi; v += ys) {
    svg += "<line x1=\"" + num(kLeft) + "\" y1=\"" + num(py(v)) + "\" x2=\"" + num(kLeft + plot_w) + "\" y2=\"" +
           num(py(v)) + "\" stroke=\"#e0e0e0\"/>\n";
    svg += "<text x=\"" + num(kLeft - 6) + "\" y=\"" + num(py(v) + 4) + "\" text-anchor=\"end\">" + tick_label(v, ys) +
           "</text>\n";
  }
  svg += "<text x=\"" + num(kLeft + plot_w / 2) + "\" y=\"" + num(options.height - 14.0) +
         "\" text-anchor=\"middle\">" + html_escape(options.x_label) + "</text>\n";
  svg += "<text transform=\"translate(18," + num(kTop + plot_h / 2) + ") rotate(-90)\" text-anchor=\"middle\">" +
         html_escape(options.y_label) + "</text>\n";

  for (const PlotSeries& s : series) {
    // A non-finite point ends one polyline and starts the next (gaps in tracking).
    std::vector<std::string> runs(1);
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
        if (!runs.back().empty()) runs.emplace_back();
        continue;
      }
      runs.back() += num(px(s.x[i])) + "," + num(py(s.y[i])) + " ";
    }
    for (const std::string& points : runs) {
      if (points.empty()) continue;
      svg += "<polyline fill=\"none\" stroke=\"" + html_escape(s.color) + "\" stroke-width=\"1.5\"" +
             (s.dashed ? " stroke-dasharray=\"6,4\"" : "") + " points=\"" + points + "\"/>\n";
    }
  }
  // Legend on a translucent box so it stays readable over the data.
  std::size_t longest = 0;
  for (const PlotSeries& s : series) longest = std::max(longest, s.label.size());
  svg += "<rect x=\"" + num(kLeft + 4) + "\" y=\"" + num(kTop + 4) + "\" width=\"" +
         num(44 + 7.0 * static_cast<double>(longest)) + "\" height=\"" + num(8 + 16.0 * static_cast<double>(series.size())) +
         "\" fill=\"white\" fill-opacity=\"0.85\" stroke=\"#cccccc\"/>\n";
  double legend_y = kTop + 16;
  for (const PlotSeries& s : series) {
    svg += "<line x1=\"" + num(kLeft + 10) + "\" y1=\"" + num(legend_y - 4) + "\" x2=\"" + num(kLeft + 34) +
           "\" y2=\"" + num(legend_y - 4) + "\" stroke=\"" + html_escape(s.color) + "\" stroke-width=\"2\"" +
           (s.dashed ? " stroke-dasharray=\"6,4\"" : "") + "/>\n";
    svg += "<text x=\"" + num(kLeft + 40) + "\" y=\"" + num(legend_y) + "\">" + html_escape(s.label) + "</text>\n";
    legend_y += 16;
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace stillslam
