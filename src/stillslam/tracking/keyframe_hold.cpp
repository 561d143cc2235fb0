#include "stillslam/tracking/keyframe_hold.h"

#include <algorithm>
#include <cstdint>

#include "stillslam/map/map_point.h"
#include "stillslam/tracking/fresh_mask_check.h"

namespace stillslam {

void KeyframeHold::note_matches(const KeyFrame& kf) const {
  if (!evidence_while_held_) return;
  for (std::size_t i = 0; i < kf.size(); ++i) {
    const MapPointPtr& mp = kf.map_point(i);
    // The keyframe's own new points already have it as their observation.
    if (mp && !mp->is_bad() && !mp->is_observed_by(&kf)) mp->note_held_observation(kf.frame_id());
  }
}

void KeyframeHold::hold(KeyFramePtr kf, std::vector<cv::Point2f> raw_pixels) {
  note_matches(*kf);
  queue_.push_back({std::move(kf), std::nullopt, std::move(raw_pixels), true});
}

int KeyframeHold::assign(std::size_t frame_index) { return assign_frame_index(queue_, frame_index); }

std::vector<KeyFramePtr> KeyframeHold::pass(KeyFramePtr kf) {
  if (queue_.empty()) return {std::move(kf)};
  note_matches(*kf);
  queue_.push_back({std::move(kf), std::nullopt, {}, false});
  return {};
}

std::size_t KeyframeHold::held() const {
  const auto waits = [](const MaskWait& e) { return e.waits; };
  return static_cast<std::size_t>(std::count_if(queue_.begin(), queue_.end(), waits));
}

KeyframeHoldRelease KeyframeHold::release(std::size_t frame_index, const std::vector<cv::Mat1b>& instances) {
  KeyframeHoldRelease out;
  while (!queue_.empty() &&
         (!queue_.front().waits || (queue_.front().frame_index && *queue_.front().frame_index <= frame_index))) {
    MaskWait e = std::move(queue_.front());
    queue_.pop_front();
    if (e.waits && *e.frame_index < frame_index) ++out.unchecked;
    if (e.waits && *e.frame_index == frame_index && !e.kf->is_bad()) {
      const std::uint64_t id = e.kf->id();
      if (evidence_while_held_) {
        // A match the mask unlinks below was not an observation after all.
        for (std::size_t i = 0; i < e.kf->size() && i < e.raw_pixels.size(); ++i) {
          const MapPointPtr& mp = e.kf->map_point(i);
          if (mp && mp->held_observation_frame() == e.kf->frame_id() && on_any_instance(instances, e.raw_pixels[i])) {
            mp->clear_held_observation();
          }
        }
      }
      const PointsInsideMask removed = remove_points_inside(
          *e.kf, e.raw_pixels, instances, [id](const MapPoint& mp) { return mp.first_keyframe_id() == id; });
      out.culled += removed.culled;
      out.unlinked += removed.unlinked;
    }
    out.keyframes.push_back(std::move(e.kf));
  }
  return out;
}

KeyframeHoldRelease KeyframeHold::release_all() {
  KeyframeHoldRelease out;
  for (MaskWait& e : queue_) {
    out.unchecked += e.waits;
    out.keyframes.push_back(std::move(e.kf));
  }
  queue_.clear();
  return out;
}

}  // namespace stillslam
