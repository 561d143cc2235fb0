#include "stillslam/map/keyframe_point_features.h"

namespace stillslam {

KeyframePointFeatures keyframe_point_features(const KeyFrame& kf, const FeatureVector& features) {
  KeyframePointFeatures out;
  out.descriptors.create(0, 32, CV_8U);
  for (const FeatureGroup& g : features) {
    FeatureGroup kept;
    kept.node = g.node;
    for (std::uint32_t i : g.features) {
      const MapPointPtr& mp = kf.map_point(i);
      if (!mp || mp->is_bad()) continue;
      kept.features.push_back(static_cast<std::uint32_t>(out.slot.size()));
      out.slot.push_back(i);
      out.descriptors.push_back(cv::Mat(1, 32, CV_8U, const_cast<std::uint8_t*>(kf.descriptor(i))));
    }
    if (!kept.features.empty()) out.groups.groups.push_back(std::move(kept));
  }
  return out;
}

}  // namespace stillslam
