#include "stillslam/tracking/keyframe_check.h"

#include <cstdint>

namespace stillslam {

void KeyframeCheck::add(KeyFramePtr kf, std::vector<cv::Point2f> raw_pixels, std::optional<std::size_t> frame_index) {
  pending_.push_back({std::move(kf), frame_index, std::move(raw_pixels)});
}

int KeyframeCheck::assign(std::size_t frame_index) { return assign_frame_index(pending_, frame_index); }

KeyframeCheckResult KeyframeCheck::check(std::size_t frame_index, const std::vector<cv::Mat1b>& instances) {
  KeyframeCheckResult out;
  // Entries are in the order their frames were tracked; a first keyframe
  // added with its (earlier) index may sit behind a later one: every entry is
  // looked at, an unassigned one stops the walk.
  for (auto it = pending_.begin(); it != pending_.end() && it->frame_index;) {
    if (*it->frame_index > frame_index) {
      ++it;
      continue;
    }
    if (*it->frame_index < frame_index) {
      ++out.unchecked;
      it = pending_.erase(it);
      continue;
    }
    KeyFrame& kf = *it->kf;
    if (!kf.is_bad()) {
      ++out.checked;
      const std::uint64_t id = kf.id();
      const bool cull_new = cull_new_points_;
      const PointsInsideMask removed =
          remove_points_inside(kf, it->raw_pixels, instances, [id, cull_new](const MapPoint& mp) {
            return mp.first_keyframe_id() == id || (cull_new && mp.first_keyframe_id() > id);
          });
      out.culled += removed.culled;
      out.unlinked += removed.unlinked;
    }
    it = pending_.erase(it);
  }
  return out;
}

KeyframeCheckResult KeyframeCheck::drop_all() {
  KeyframeCheckResult out;
  out.unchecked = static_cast<int>(pending_.size());
  pending_.clear();
  return out;
}

}  // namespace stillslam
