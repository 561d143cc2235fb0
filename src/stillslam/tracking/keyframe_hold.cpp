#include "stillslam/tracking/keyframe_hold.h"

#include <algorithm>
#include <cstdint>

namespace stillslam {

void KeyframeHold::hold(KeyFramePtr kf, std::vector<cv::Point2f> raw_pixels) {
  queue_.push_back({std::move(kf), std::nullopt, std::move(raw_pixels), true});
}

int KeyframeHold::assign(std::size_t frame_index) { return assign_frame_index(queue_, frame_index); }

std::vector<KeyFramePtr> KeyframeHold::pass(KeyFramePtr kf) {
  if (queue_.empty()) return {std::move(kf)};
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
