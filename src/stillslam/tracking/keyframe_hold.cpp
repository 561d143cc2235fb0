#include "stillslam/tracking/keyframe_hold.h"

#include <algorithm>

#include "stillslam/tracking/fresh_mask_check.h"

namespace stillslam {

void KeyframeHold::hold(KeyFramePtr kf, std::vector<cv::Point2f> raw_pixels) {
  queue_.push_back({std::move(kf), true, std::nullopt, std::move(raw_pixels)});
}

int KeyframeHold::assign(std::size_t frame_index) {
  int n = 0;
  for (Entry& e : queue_) {
    if (!e.held || e.frame_index) continue;
    e.frame_index = frame_index;
    ++n;
  }
  return n;
}

std::vector<KeyFramePtr> KeyframeHold::pass(KeyFramePtr kf) {
  if (queue_.empty()) return {std::move(kf)};
  queue_.push_back({std::move(kf), false, std::nullopt, {}});
  return {};
}

std::size_t KeyframeHold::held() const {
  return static_cast<std::size_t>(std::count_if(queue_.begin(), queue_.end(), [](const Entry& e) { return e.held; }));
}

KeyframeHoldRelease KeyframeHold::release(std::size_t frame_index, const std::vector<cv::Mat1b>& instances) {
  KeyframeHoldRelease out;
  while (!queue_.empty() &&
         (!queue_.front().held || (queue_.front().frame_index && *queue_.front().frame_index <= frame_index))) {
    Entry e = std::move(queue_.front());
    queue_.pop_front();
    if (e.held && *e.frame_index < frame_index) ++out.unchecked;
    if (e.held && *e.frame_index == frame_index && !e.kf->is_bad()) {
      KeyFrame* kf = e.kf.get();
      for (std::size_t i = 0; i < kf->size() && i < e.raw_pixels.size(); ++i) {
        const MapPointPtr mp = kf->map_point(i);
        if (!mp || mp->is_bad() || !on_any_instance(instances, e.raw_pixels[i])) continue;
        if (mp->first_keyframe_id() == kf->id()) {
          mp->set_bad();
          ++out.culled;
        } else {
          kf->erase_map_point(i);
          mp->erase_observation(kf);
          ++out.unlinked;
        }
      }
    }
    out.keyframes.push_back(std::move(e.kf));
  }
  return out;
}

KeyframeHoldRelease KeyframeHold::release_all() {
  KeyframeHoldRelease out;
  for (Entry& e : queue_) {
    out.unchecked += e.held;
    out.keyframes.push_back(std::move(e.kf));
  }
  queue_.clear();
  return out;
}

}  // namespace stillslam
