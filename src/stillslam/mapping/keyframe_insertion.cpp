#include "stillslam/mapping/keyframe_insertion.h"

namespace stillslam {

void register_keyframe(KeyFrame& kf, std::vector<MapPointPtr>& recent) {
  const ScalePyramid& pyramid = kf.setup().pyramid;
  for (std::size_t i = 0; i < kf.size(); ++i) {
    MapPointPtr mp = kf.map_point(i);
    if (!mp) continue;
    if (mp->is_bad()) {
      kf.erase_map_point(i);
      continue;
    }
    if (!mp->is_observed_by(&kf)) {
      mp->add_observation(&kf, i);
      mp->update_normal_and_depth(pyramid);
      mp->compute_distinctive_descriptor();
    } else {
      recent.push_back(mp);
    }
  }
  kf.update_connections();
}

}  // namespace stillslam
