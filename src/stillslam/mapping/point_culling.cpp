#include "stillslam/mapping/point_culling.h"

#include "stillslam/core/option_check.h"

namespace stillslam {

int cull_recent_points(std::vector<MapPointPtr>& recent, std::uint64_t current_keyframe_id,
                       const PointCullingOptions& options) {
  int culled = 0;
  std::vector<MapPointPtr> kept;
  kept.reserve(recent.size());
  for (MapPointPtr& mp : recent) {
    if (mp->is_bad()) continue;
    if (mp->is_provisional()) {  // judged once confirmed, its age counted from then
      kept.push_back(std::move(mp));
      continue;
    }
    const std::uint64_t start = mp->culling_start_keyframe_id();
    const std::uint64_t age = current_keyframe_id > start ? current_keyframe_id - start : 0;
    if (mp->found_ratio() < options.min_found_ratio ||
        (age >= 2 && mp->num_observations() <= options.min_observations)) {
      mp->set_bad();
      ++culled;
      continue;
    }
    if (age >= 3) continue;  // survived: no longer recent
    kept.push_back(std::move(mp));
  }
  recent = std::move(kept);
  return culled;
}

void PointCullingOptions::check() const {
  using namespace option_check;
  in_range("PointCullingOptions.min_found_ratio", min_found_ratio, 0, 1);
  at_least("PointCullingOptions.min_observations", min_observations, 0);
}

}  // namespace stillslam
