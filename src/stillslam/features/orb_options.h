#pragma once

namespace stillslam {

// ORB extraction settings, named as ORB-SLAM3's ORBextractor.* keys.
struct OrbOptions {
  int n_features = 1000;     // ORBextractor.nFeatures
  float scale_factor = 1.2f; // ORBextractor.scaleFactor
  int n_levels = 8;          // ORBextractor.nLevels
  int ini_th_fast = 20;      // ORBextractor.iniThFAST
  int min_th_fast = 7;       // ORBextractor.minThFAST
  // Side of the square cells (level pixels) in which FAST runs with its own
  // threshold fallback; small cells let weakly textured regions contribute.
  int fast_cell_size = 30;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

}  // namespace stillslam
