#include "stillslam/publish/map_snapshot.h"

#include <unordered_map>

namespace stillslam {

MapSnapshot snapshot_map(const Map& map, int min_covisibility_weight) {
  MapSnapshot out;
  out.map_id = map.id();
  const std::vector<KeyFramePtr> keyframes = map.keyframes();
  std::unordered_map<const KeyFrame*, std::size_t> index;
  out.keyframes.reserve(keyframes.size());
  for (const KeyFramePtr& kf : keyframes) {
    index.emplace(kf.get(), out.keyframes.size());
    out.keyframes.push_back({kf->id(), kf->T_world_cam()});
  }
  for (const KeyFramePtr& kf : keyframes) {
    const std::size_t a = index.at(kf.get());
    for (KeyFrame* other : kf->covisibles_with_weight(min_covisibility_weight)) {
      const auto it = index.find(other);
      if (it != index.end() && it->second > a) out.covisibility.emplace_back(a, it->second);
    }
  }
  const std::vector<MapPointPtr> points = map.map_points();
  out.points.reserve(points.size());
  for (const MapPointPtr& mp : points) {
    if (!mp->is_bad()) out.points.push_back(mp->position().cast<float>());
  }
  return out;
}

}  // namespace stillslam
