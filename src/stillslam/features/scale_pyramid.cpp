#include "stillslam/features/scale_pyramid.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "stillslam/core/error.h"

namespace stillslam {

ScalePyramid::ScalePyramid(const OrbOptions& options)
    : ScalePyramid(options.n_levels, options.scale_factor) {}

ScalePyramid::ScalePyramid(int levels, float factor) : n_levels(levels), scale_factor(factor) {
  if (n_levels < 1) {
    throw Error("ORBextractor.nLevels must be >= 1 (got " + std::to_string(n_levels) + ")");
  }
  if (n_levels > 1 && !(scale_factor > 1.f)) {
    throw Error("ORBextractor.scaleFactor must be > 1 when nLevels > 1 (got " +
                std::to_string(scale_factor) + "); ORB-SLAM's usual value is 1.2");
  }
  scale.resize(n_levels);
  inv_scale.resize(n_levels);
  sigma2.resize(n_levels);
  inv_sigma2.resize(n_levels);
  double s = 1.0;
  for (int l = 0; l < n_levels; ++l) {
    scale[l] = static_cast<float>(s);
    inv_scale[l] = static_cast<float>(1.0 / s);
    sigma2[l] = static_cast<float>(s * s);
    inv_sigma2[l] = static_cast<float>(1.0 / (s * s));
    s *= scale_factor;
  }
}

int ScalePyramid::level_for_scale(float scale_ratio) const {
  if (n_levels == 1 || !(scale_ratio > 1.f)) return 0;
  const int level = static_cast<int>(std::ceil(std::log(scale_ratio) / std::log(scale_factor)));
  return std::clamp(level, 0, n_levels - 1);
}

}  // namespace stillslam
