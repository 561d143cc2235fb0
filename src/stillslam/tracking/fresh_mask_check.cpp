#include "stillslam/tracking/fresh_mask_check.h"

#include <algorithm>

namespace stillslam {

bool on_any_instance(const std::vector<cv::Mat1b>& instances, const cv::Point2f& pixel) {
  const cv::Point p(cvRound(pixel.x), cvRound(pixel.y));
  return std::any_of(instances.begin(), instances.end(), [&](const cv::Mat1b& m) {
    return cv::Rect(0, 0, m.cols, m.rows).contains(p) && m(p) != 0;
  });
}

void FreshMaskCheck::remember(std::size_t frame_index, const Frame& frame) {
  std::vector<Seen> seen;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (const MapPointPtr& mp = frame.map_point(i); mp && !mp->is_bad()) {
      seen.push_back({frame.keypoints_raw()[i].pt, mp});
    }
  }
  seen_[frame_index] = std::move(seen);
}

int FreshMaskCheck::apply(std::size_t frame_index, const std::vector<cv::Mat1b>& instances) {
  int culled = 0;
  const auto it = seen_.find(frame_index);
  if (it != seen_.end()) {
    for (const Seen& s : it->second) {
      if (!on_any_instance(instances, s.pixel) || s.point->is_bad()) continue;
      s.point->set_bad();
      ++culled;
    }
  }
  seen_.erase(seen_.begin(), seen_.upper_bound(frame_index));
  return culled;
}

}  // namespace stillslam
