#include "stillslam/map/keyframe_point_features.h"

namespace stillslam {

namespace {

template <typename HasPoint>
KeyframePointFeatures gather(const KeyFrame& kf, const FeatureVector& features, HasPoint has_point) {
  KeyframePointFeatures out;
  out.descriptors.create(0, 32, CV_8U);
  for (const FeatureGroup& g : features) {
    FeatureGroup kept;
    kept.node = g.node;
    for (std::uint32_t i : g.features) {
      if (!has_point(i)) continue;
      kept.features.push_back(static_cast<std::uint32_t>(out.slot.size()));
      out.slot.push_back(i);
      out.descriptors.push_back(cv::Mat(1, 32, CV_8U, const_cast<std::uint8_t*>(kf.descriptor(i))));
    }
    if (!kept.features.empty()) out.groups.groups.push_back(std::move(kept));
  }
  return out;
}

}  // namespace

KeyframePointFeatures keyframe_point_features(const KeyFrame& kf, const FeatureVector& features) {
  return gather(kf, features, [&](std::uint32_t i) {
    const MapPointPtr& mp = kf.map_point(i);
    return mp && !mp->is_bad() && !mp->is_provisional();
  });
}

KeyframePointFeatures keyframe_point_features(const KeyFrame& kf, const std::vector<std::int32_t>& point_index,
                                              const FeatureVector& features) {
  return gather(kf, features, [&](std::uint32_t i) { return point_index[i] >= 0; });
}

}  // namespace stillslam
