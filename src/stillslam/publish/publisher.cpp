#include "stillslam/publish/publisher.h"

#include "stillslam/core/error.h"

namespace stillslam {

void PublishOptions::check() const {
  if (map_every_frames < 0) {
    throw Error("PublishOptions.map_every_frames = " + std::to_string(map_every_frames) + ": must be >= 0");
  }
  if (min_covisibility_weight < 1) {
    throw Error("PublishOptions.min_covisibility_weight = " + std::to_string(min_covisibility_weight) +
                ": must be >= 1");
  }
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
