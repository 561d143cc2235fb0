#include "stillslam/io/distortion_check.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stillslam {
namespace {

std::string pixel_text(double u, double v) {
  return "at pixel (" + std::to_string(static_cast<long long>(std::lround(u))) + ", " +
         std::to_string(static_cast<long long>(std::lround(v))) + ")";
}

// OpenCV's radial-tangential model: Jacobian determinant of
// (x, y) -> (x r + 2 p1 x y + p2 (r2 + 2 x^2), y r + p1 (r2 + 2 y^2) + 2 p2 x y), r = 1 + k1 r2 + k2 r4 + k3 r6.
double radtan_jacobian(const std::vector<double>& d, double x, double y) {
  const double k1 = d[0], k2 = d[1], p1 = d[2], p2 = d[3], k3 = d.size() > 4 ? d[4] : 0.0;
  const double r2 = x * x + y * y;
  const double radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
  const double dradial_dr2 = k1 + r2 * (2 * k2 + 3 * k3 * r2);
  const double dxx = radial + 2 * x * x * dradial_dr2 + 2 * p1 * y + 6 * p2 * x;
  const double dxy = 2 * x * y * dradial_dr2 + 2 * p1 * x + 2 * p2 * y;
  const double dyx = 2 * x * y * dradial_dr2 + 2 * p1 * x + 2 * p2 * y;
  const double dyy = radial + 2 * y * y * dradial_dr2 + 6 * p1 * y + 2 * p2 * x;
  return dxx * dyy - dxy * dyx;
}

}  // namespace

std::optional<std::string> distortion_fold(const CameraCalibration& c) {
  if (c.distortion.empty() || c.fx <= 0 || c.fy <= 0) return std::nullopt;
  const double width = c.width > 0 ? c.width : 2 * std::max(c.cx, 1.0);
  const double height = c.height > 0 ? c.height : 2 * std::max(c.cy, 1.0);
  // Ideal normalized coordinates of the image's extent, 10 % beyond it.
  const double x0 = (0 - c.cx) / c.fx * 1.1, x1 = (width - c.cx) / c.fx * 1.1;
  const double y0 = (0 - c.cy) / c.fy * 1.1, y1 = (height - c.cy) / c.fy * 1.1;
  constexpr int kSteps = 40;
  if (c.model == CameraModel::KannalaBrandt8) {
    if (c.distortion.size() < 4) return std::nullopt;
    const auto& k = c.distortion;
    const double r_max = std::max({std::hypot(x0, y0), std::hypot(x1, y0), std::hypot(x0, y1), std::hypot(x1, y1)});
    const double theta_max = std::min(std::numbers::pi / 2, r_max);
    for (int i = 0; i <= kSteps; ++i) {
      const double t = theta_max * i / kSteps, t2 = t * t;
      // d/dtheta of theta (1 + k1 t^2 + k2 t^4 + k3 t^6 + k4 t^8)
      const double slope = 1 + t2 * (3 * k[0] + t2 * (5 * k[1] + t2 * (7 * k[2] + t2 * 9 * k[3])));
      if (!(slope > 0)) return "at " + std::to_string(static_cast<int>(std::lround(t * 180 / std::numbers::pi))) +
                                      " degrees from the optical axis";
    }
    return std::nullopt;
  }
  if (c.distortion.size() < 4) return std::nullopt;
  for (int i = 0; i <= kSteps; ++i) {
    for (int j = 0; j <= kSteps; ++j) {
      const double x = x0 + (x1 - x0) * i / kSteps, y = y0 + (y1 - y0) * j / kSteps;
      if (!(radtan_jacobian(c.distortion, x, y) > 0)) return pixel_text(c.cx + c.fx * x, c.cy + c.fy * y);
    }
  }
  return std::nullopt;
}

}  // namespace stillslam
