#include "stillslam/tracking/local_map.h"

#include <map>
#include <set>
#include <unordered_set>

namespace stillslam {

LocalMap build_local_map(const Frame& frame, KeyFrame* fallback, std::size_t max_keyframes) {
  LocalMap local;
  std::map<KeyFrame*, int, KeyFrameIdLess> counter;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const MapPointPtr& mp = frame.map_point(i);
    if (!mp || mp->is_bad() || frame.is_outlier(i)) continue;
    for (const auto& [kf, idx] : mp->observations()) ++counter[kf];
  }
  std::set<KeyFrame*, KeyFrameIdLess> included;
  int best = 0;
  for (const auto& [kf, n] : counter) {
    if (kf->is_bad()) continue;
    local.keyframes.push_back(kf);
    included.insert(kf);
    if (n > best) {
      best = n;
      local.reference = kf;
    }
  }
  if (local.keyframes.empty() && fallback != nullptr && !fallback->is_bad()) {
    local.keyframes.push_back(fallback);
    included.insert(fallback);
    local.reference = fallback;
  }
  // Neighbours of the seeds: best covisibles, children, parent.
  const std::size_t seeds = local.keyframes.size();
  for (std::size_t s = 0; s < seeds && local.keyframes.size() < max_keyframes; ++s) {
    KeyFrame* kf = local.keyframes[s];
    for (KeyFrame* n : kf->best_covisibles(10)) {
      if (!n->is_bad() && included.insert(n).second) {
        local.keyframes.push_back(n);
        break;
      }
    }
    for (KeyFrame* c : kf->children()) {
      if (!c->is_bad() && included.insert(c).second) {
        local.keyframes.push_back(c);
        break;
      }
    }
    KeyFrame* p = kf->parent();
    if (p != nullptr && !p->is_bad() && included.insert(p).second) local.keyframes.push_back(p);
  }
  std::unordered_set<const MapPoint*> seen;
  for (KeyFrame* kf : local.keyframes) {
    for (const MapPointPtr& mp : kf->map_points()) {
      if (mp && !mp->is_bad() && !mp->is_provisional() && seen.insert(mp.get()).second) local.points.push_back(mp);
    }
  }
  return local;
}

}  // namespace stillslam
