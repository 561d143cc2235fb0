#pragma once
// Outlier thresholds shared by the optimizers: chi-square quantiles at 95%
// for whitened reprojection errors with 2 (mono) or 3 (stereo/RGB-D) dof.

namespace stillslam {

inline constexpr double kChi2Mono95 = 5.991;
inline constexpr double kChi2Stereo95 = 7.815;

}  // namespace stillslam
