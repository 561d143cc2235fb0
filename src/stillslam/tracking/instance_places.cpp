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

double InstancePlaces::distance(const Place& place, const Eigen::Vector3d& p_world) {
  return std::min((place.p_world - p_world).norm(), (place.p_most - p_world).norm());
}

std::map<std::uint32_t, std::uint32_t> InstancePlaces::assign(const std::vector<PlaceClaim>& claims,
                                                              std::set<std::uint32_t> present) const {
  std::map<std::uint32_t, std::uint32_t> out;
  if (options_.radius_m <= 0) return out;  // matching off
  for (const PlaceClaim& c : claims) present.insert(c.id);
  std::vector<bool> done(claims.size(), false);
  std::set<std::uint32_t> closed;  // remembered instances taken or blocked this frame
  for (;;) {
    std::size_t best_claim = claims.size();
    std::uint32_t best_place = 0;
    double best_d = options_.radius_m;
    for (std::size_t k = 0; k < claims.size(); ++k) {
      if (done[k]) continue;
      for (const auto& [id, p] : places_) {
        if (!p.known || p.category != claims[k].category || present.count(id) || closed.count(id)) continue;
        const double d = distance(p, claims[k].p_world);
        if (d <= best_d) {
          best_d = d;
          best_claim = k;
          best_place = id;
        }
      }
    }
    if (best_claim == claims.size()) break;
    const PlaceClaim& c = claims[best_claim];
    done[best_claim] = true;  // its nearest remembered instance: farther ones are no better
    closed.insert(best_place);
    bool jumped = false;
    if (!c.is_new) {
      const auto own = places_.find(c.id);
      if (own != places_.end() && own->second.known) {
        const double d_own = (own->second.p_world - c.p_world).norm();
        jumped = d_own > 0.5 * options_.radius_m && d_own > 2 * best_d;
      }
    }
    if (!c.is_new && !jumped) continue;  // it stands there under its own id: blocked
    out[c.id] = best_place;
    present.erase(c.id);
    present.insert(best_place);
  }
  return out;
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
