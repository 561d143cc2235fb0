#include "stillslam/tracking/start_evidence.h"

namespace stillslam {

void StartEvidence::begin(const std::vector<MapPointPtr>& points, std::uint64_t last_frame) {
  ids_.clear();
  for (const MapPointPtr& mp : points) {
    if (mp) ids_.insert(mp->id());
  }
  last_frame_ = last_frame;
  active_ = !ids_.empty();
}

void StartEvidence::reset() {
  ids_.clear();
  last_frame_ = 0;
  active_ = false;
}

bool StartEvidence::holds(const MapPoint& point, std::uint64_t frame_id) const {
  return active(frame_id) && !point.is_bad() && ids_.count(point.id()) > 0;
}

}  // namespace stillslam
