#pragma once
// Hamming-distance thresholds of guided matching (256-bit descriptors): HIGH
// for tracking against predicted positions, LOW where a wrong match would
// create or merge map points.
namespace stillslam {

inline constexpr int kDescriptorDistanceHigh = 100;
inline constexpr int kDescriptorDistanceLow = 50;

}  // namespace stillslam
