#include "stillslam/map/ba_observations.h"

#include "stillslam/map/keyframe.h"

namespace stillslam {

std::size_t append_ba_observations(const MapPoint& mp, std::size_t point, const BaKeyFrameIndex& keyframes,
                                   const ScalePyramid& pyramid, std::vector<BaObservation>& observations,
                                   std::vector<std::size_t>* keypoint_index) {
  std::size_t appended = 0;
  for (const auto& [kf, idx] : mp.observations()) {
    const auto it = keyframes.find(kf);
    if (it == keyframes.end()) continue;
    BaObservation o;
    o.keyframe = it->second;
    o.point = point;
    const cv::KeyPoint& kp = kf->keypoint(idx);
    o.pixel = Eigen::Vector2d(kp.pt.x, kp.pt.y);
    o.u_right = kf->u_right(idx);
    o.inv_sigma2 = pyramid.inv_sigma2[static_cast<std::size_t>(kp.octave)];
    observations.push_back(o);
    if (keypoint_index) keypoint_index->push_back(idx);
    ++appended;
  }
  return appended;
}

}  // namespace stillslam
