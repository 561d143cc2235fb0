#pragma once
// Outlier thresholds shared by the optimizers: chi-square quantiles at 95%
// for whitened reprojection errors with 2 (mono) or 3 (stereo/RGB-D) dof, and
// 1 dof for the right-image row of a stereo observation on its own.

namespace stillslam {

inline constexpr double kChi2Mono95 = 5.991;
inline constexpr double kChi2Stereo95 = 7.815;
inline constexpr double kChi2OneDof95 = 3.841;

}  // namespace stillslam
