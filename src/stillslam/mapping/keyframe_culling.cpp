#include "stillslam/mapping/keyframe_culling.h"

#include "stillslam/core/option_check.h"

namespace stillslam {

double keyframe_redundancy(const KeyFrame& kf, const KeyFrameCullingOptions& options) {
  int points = 0, redundant = 0;
  const double close_depth = kf.setup().close_depth;
  for (std::size_t i = 0; i < kf.size(); ++i) {
    const MapPointPtr& mp = kf.map_point(i);
    if (!mp || mp->is_bad()) continue;  // a provisional point counts: seen by this keyframe alone
    const float z = kf.depth(i);
    if (z < 0 || z > close_depth) continue;
    ++points;
    if (mp->num_observations() <= options.min_observers) continue;
    const int level = kf.keypoint(i).octave;
    int observers = 0;
    for (const auto& [other, idx] : mp->observations()) {
      if (other == &kf) continue;
      if (other->keypoint(idx).octave <= level + 1 && ++observers >= options.min_observers) break;
    }
    if (observers >= options.min_observers) ++redundant;
  }
  return points > 0 ? static_cast<double>(redundant) / points : 0.0;
}

int cull_redundant_keyframes(Map& map, KeyFrame& kf, const KeyFrameCullingOptions& options,
                             std::vector<std::uint64_t>* culled_ids) {
  int culled = 0;
  for (KeyFrame* other : kf.covisibles()) {
    if (other->is_origin() || other->is_bad()) continue;
    if (keyframe_redundancy(*other, options) > options.redundancy) {
      map.erase_keyframe(map.keyframe(other->id()));
      if (other->is_bad()) {
        ++culled;
        if (culled_ids) culled_ids->push_back(other->id());
      }
    }
  }
  return culled;
}

void KeyFrameCullingOptions::check() const {
  using namespace option_check;
  in_half_open("KeyFrameCullingOptions.redundancy", redundancy, 0, 1);
  at_least("KeyFrameCullingOptions.min_observers", min_observers, 1);
}

}  // namespace stillslam
