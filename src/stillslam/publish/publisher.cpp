#include "stillslam/publish/publisher.h"

#include "stillslam/core/option_check.h"

namespace stillslam {

void PublishOptions::check() const {
  using namespace option_check;
  at_least("PublishOptions.map_every_frames", map_every_frames, 0);
  at_least("PublishOptions.min_covisibility_weight", min_covisibility_weight, 1);
}

std::size_t AtlasSnapshot::num_keyframes() const {
  std::size_t n = 0;
  for (const MapSnapshot& m : maps) n += m.keyframes.size();
  return n;
}

std::size_t AtlasSnapshot::num_points() const {
  std::size_t n = 0;
  for (const MapSnapshot& m : maps) n += m.points.size();
  return n;
}

}  // namespace stillslam
