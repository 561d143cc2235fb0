#include "stillslam/tracking/instance_places.h"

#include <algorithm>

#include "stillslam/core/option_check.h"

namespace stillslam {

void InstancePlacesOptions::check() const {
  using namespace option_check;
  at_least("InstancePlacesOptions.radius_m", radius_m, 0.0);
  at_least("InstancePlacesOptions.memory_frames", memory_frames, 0);
}

InstancePlaces::InstancePlaces(InstancePlacesOptions options) : options_(options) { options_.check(); }

void InstancePlaces::seen(std::uint32_t id, const std::string& category, std::int64_t frame,
                          const Eigen::Vector3d* p_world, int pixels) {
  Place& p = places_[id];
  p.category = category;
  p.last_frame = frame;
  if (p_world) {
    p.known = true;
    p.p_world = *p_world;
    if (pixels > p.most_pixels) {
      p.most_pixels = pixels;
      p.p_most = *p_world;
    }
  }
}

std::uint32_t InstancePlaces::match(const std::string& category, const Eigen::Vector3d& p_world,
                                    const std::set<std::uint32_t>& present) const {
  std::uint32_t best = 0;
  if (options_.radius_m <= 0) return best;  // matching off
  double best_d = options_.radius_m;
  for (const auto& [id, p] : places_) {
    if (!p.known || p.category != category || present.count(id)) continue;
    const double d = std::min((p.p_world - p_world).norm(), (p.p_most - p_world).norm());
    if (d <= best_d) {
      best_d = d;
      best = id;
    }
  }
  return best;
}

std::vector<std::uint32_t> InstancePlaces::expire(std::int64_t frame) {
  std::vector<std::uint32_t> out;
  for (auto it = places_.begin(); it != places_.end();) {
    if (frame - it->second.last_frame > options_.memory_frames) {
      out.push_back(it->first);
      it = places_.erase(it);
    } else {
      ++it;
    }
  }
  return out;
}

}  // namespace stillslam
