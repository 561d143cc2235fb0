#include "stillslam/settings/section_binders.h"
#include "stillslam/settings/section_keys.h"

namespace stillslam {

// ORB-SLAM3's ORBextractor.* keys, unchanged.
void bind_orb(const YamlReader& yaml, OrbOptions& orb) {
  SectionKeys keys(yaml, "ORBextractor", false);
  keys.integer("nFeatures", orb.n_features, "OrbOptions.n_features", {100, 50000});
  keys.number("scaleFactor", orb.scale_factor, "OrbOptions.scale_factor", {1, 2});
  keys.integer("nLevels", orb.n_levels, "OrbOptions.n_levels", {1, 16});
  keys.integer("iniThFAST", orb.ini_th_fast, "OrbOptions.ini_th_fast", {1, 254});
  keys.integer("minThFAST", orb.min_th_fast, "OrbOptions.min_th_fast", {1, 254});
  keys.check([&] { orb.check(); });
}

}  // namespace stillslam
