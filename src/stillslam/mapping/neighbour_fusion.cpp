#include "stillslam/mapping/neighbour_fusion.h"

#include <set>
#include <unordered_set>

#include "stillslam/core/option_check.h"
#include "stillslam/map/fuse.h"

namespace stillslam {

int fuse_with_neighbours(KeyFrame& kf, const FusionOptions& options) {
  std::vector<KeyFrame*> targets;
  std::set<KeyFrame*, KeyFrameIdLess> included{&kf};
  for (KeyFrame* n : kf.best_covisibles(options.neighbours)) {
    if (n->is_bad() || !included.insert(n).second) continue;
    targets.push_back(n);
  }
  const std::size_t first_order = targets.size();
  for (std::size_t t = 0; t < first_order; ++t) {
    for (KeyFrame* n2 : targets[t]->best_covisibles(options.second_neighbours)) {
      if (n2->is_bad() || !included.insert(n2).second) continue;
      targets.push_back(n2);
    }
  }

  int fused = 0;
  std::vector<MapPointPtr> own;
  for (const MapPointPtr& mp : kf.map_points()) {
    if (mp) own.push_back(mp);
  }
  for (KeyFrame* target : targets) fused += fuse(*target, own);

  std::vector<MapPointPtr> candidates;
  std::unordered_set<const MapPoint*> seen;
  for (KeyFrame* target : targets) {
    for (const MapPointPtr& mp : target->map_points()) {
      if (mp && !mp->is_bad() && seen.insert(mp.get()).second) candidates.push_back(mp);
    }
  }
  fused += fuse(kf, candidates);

  const ScalePyramid& pyramid = kf.setup().pyramid;
  for (const MapPointPtr& mp : kf.map_points()) {
    if (mp && !mp->is_bad()) {
      mp->compute_distinctive_descriptor();
      mp->update_normal_and_depth(pyramid);
    }
  }
  kf.update_connections();
  return fused;
}

void FusionOptions::check() const {
  using namespace option_check;
  at_least("FusionOptions.neighbours", static_cast<double>(neighbours), 1);
  at_least("FusionOptions.second_neighbours", static_cast<double>(second_neighbours), 0);
}

}  // namespace stillslam
