#include "stillslam/tracking/provisional_points.h"

#include <optional>

#include "stillslam/tracking/fresh_mask_check.h"

namespace stillslam {
namespace {

// Confirms (or, with a mask, culls inside it) a keyframe's provisional points.
void settle(KeyFrame& kf, const std::vector<cv::Point2f>* pixels, const std::vector<cv::Mat1b>& instances,
            std::uint64_t next_keyframe_id, ProvisionalCheck& out) {
  if (kf.is_bad()) return;
  out.settled.push_back(kf.shared_from_this());
  for (std::size_t i = 0; i < kf.size(); ++i) {
    const MapPointPtr mp = kf.map_point(i);
    if (!mp || mp->is_bad()) continue;
    const bool inside = pixels != nullptr && i < pixels->size() && on_any_instance(instances, (*pixels)[i]);
    if (mp->is_provisional() && mp->first_keyframe_id() == kf.id()) {
      if (inside) {
        mp->set_bad();
        ++out.culled;
      } else {
        // Placed again from the keyframe's depth and its pose now (local BA
        // moved the keyframe, not the point, while it waited).
        if (const std::optional<Eigen::Vector3d> p = kf.unproject(i)) mp->set_position(*p);
        mp->update_normal_and_depth(kf.setup().pyramid);
        mp->confirm(next_keyframe_id);
        ++out.confirmed;
      }
    } else if (inside) {
      kf.erase_map_point(i);
      mp->erase_observation(&kf);
      ++out.unlinked;
    }
  }
}

}  // namespace

void ProvisionalPoints::add(KeyFramePtr kf, std::vector<cv::Point2f> raw_pixels) {
  pending_.push_back({std::move(kf), std::nullopt, std::move(raw_pixels)});
}

int ProvisionalPoints::assign(std::size_t frame_index) { return assign_frame_index(pending_, frame_index); }

ProvisionalCheck ProvisionalPoints::check(std::size_t frame_index, const std::vector<cv::Mat1b>& instances,
                                          std::uint64_t next_keyframe_id) {
  ProvisionalCheck out;
  while (!pending_.empty() && pending_.front().frame_index && *pending_.front().frame_index <= frame_index) {
    MaskWait e = std::move(pending_.front());
    pending_.pop_front();
    if (*e.frame_index < frame_index) {
      ++out.unchecked;
      settle(*e.kf, nullptr, instances, next_keyframe_id, out);
    } else {
      settle(*e.kf, &e.raw_pixels, instances, next_keyframe_id, out);
    }
  }
  return out;
}

ProvisionalCheck ProvisionalPoints::confirm_all(std::uint64_t next_keyframe_id) {
  ProvisionalCheck out;
  for (MaskWait& e : pending_) {
    ++out.unchecked;
    settle(*e.kf, nullptr, {}, next_keyframe_id, out);
  }
  pending_.clear();
  return out;
}

}  // namespace stillslam
