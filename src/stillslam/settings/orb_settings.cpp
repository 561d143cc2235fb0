#include "stillslam/settings/section_binders.h"
#include "stillslam/settings/section_keys.h"

namespace stillslam {

// ORB-SLAM3's ORBextractor.* keys, unchanged.
void bind_orb(const YamlReader& yaml, OrbOptions& orb) {
  SectionKeys keys(yaml, "ORBextractor", false);
  keys.integer("nFeatures", orb.n_features, "OrbOptions.n_features");
  keys.number("scaleFactor", orb.scale_factor, "OrbOptions.scale_factor");
  keys.integer("nLevels", orb.n_levels, "OrbOptions.n_levels");
  keys.integer("iniThFAST", orb.ini_th_fast, "OrbOptions.ini_th_fast");
  keys.integer("minThFAST", orb.min_th_fast, "OrbOptions.min_th_fast");
  keys.check([&] { orb.check(); });
}

}  // namespace stillslam
