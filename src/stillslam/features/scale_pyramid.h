#pragma once
// Per-level scale numbers of an image pyramid: level l is the original image
// shrunk by scale[l] = scale_factor^l. sigma2 is the squared scale, used to
// weight reprojection errors of features detected on that level.
#include <vector>

#include "stillslam/features/orb_options.h"

namespace stillslam {

struct ScalePyramid {
  int n_levels = 1;
  float scale_factor = 1.f;
  std::vector<float> scale, inv_scale, sigma2, inv_sigma2;

  explicit ScalePyramid(const OrbOptions& options);
  ScalePyramid(int n_levels, float scale_factor);

  // Smallest level whose scale is >= `scale_ratio` (e.g. the predicted level of
  // a map point seen from a new distance), clamped to [0, n_levels - 1].
  int level_for_scale(float scale_ratio) const;
};

}  // namespace stillslam
