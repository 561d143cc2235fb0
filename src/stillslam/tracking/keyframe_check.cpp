#include "stillslam/tracking/keyframe_check.h"

#include "stillslam/tracking/fresh_mask_check.h"

namespace stillslam {

void KeyframeCheck::add(KeyFramePtr kf, std::vector<cv::Point2f> raw_pixels, std::optional<std::size_t> frame_index) {
  pending_.push_back({std::move(kf), frame_index, std::move(raw_pixels)});
}

int KeyframeCheck::assign(std::size_t frame_index) {
  int n = 0;
  for (Entry& e : pending_) {
    if (e.frame_index) continue;
    e.frame_index = frame_index;
    ++n;
  }
  return n;
}

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
      for (std::size_t i = 0; i < kf.size() && i < it->raw_pixels.size(); ++i) {
        const MapPointPtr mp = kf.map_point(i);
        if (!mp || mp->is_bad() || !on_any_instance(instances, it->raw_pixels[i])) continue;
        const bool own = mp->first_keyframe_id() == kf.id();
        const bool newer = mp->first_keyframe_id() > kf.id();
        if (own || (cull_new_points_ && newer)) {
          mp->set_bad();
          ++out.culled;
        } else {
          kf.erase_map_point(i);
          mp->erase_observation(&kf);
          ++out.unlinked;
        }
      }
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
