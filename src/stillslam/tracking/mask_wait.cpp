#include "stillslam/tracking/mask_wait.h"

#include "stillslam/tracking/fresh_mask_check.h"

namespace stillslam {

int assign_frame_index(std::deque<MaskWait>& queue, std::size_t frame_index) {
  int n = 0;
  for (MaskWait& e : queue) {
    if (!e.waits || e.frame_index) continue;
    e.frame_index = frame_index;
    ++n;
  }
  return n;
}

PointsInsideMask remove_points_inside(KeyFrame& kf, const std::vector<cv::Point2f>& raw_pixels,
                                      const std::vector<cv::Mat1b>& instances,
                                      const std::function<bool(const MapPoint&)>& cull) {
  PointsInsideMask out;
  for (std::size_t i = 0; i < kf.size() && i < raw_pixels.size(); ++i) {
    const MapPointPtr mp = kf.map_point(i);
    if (!mp || mp->is_bad() || !on_any_instance(instances, raw_pixels[i])) continue;
    if (cull(*mp)) {
      mp->set_bad();
      ++out.culled;
    } else {
      kf.erase_map_point(i);
      mp->erase_observation(&kf);
      ++out.unlinked;
    }
  }
  return out;
}

}  // namespace stillslam
