#include "stillslam/map/atlas.h"

#include <algorithm>
#include <string>

#include "stillslam/core/error.h"

namespace stillslam {

Atlas::Atlas() : ids_(std::make_shared<MapIdCounters>()) { create_map(); }

Map& Atlas::create_map() {
  std::lock_guard<std::mutex> lock(mutex_);
  maps_.push_back(std::make_unique<Map>(next_map_id_++, ids_));
  active_ = maps_.back()->id();
  return *maps_.back();
}

Map& Atlas::add_map(std::unique_ptr<Map> map) {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::uint64_t id = map->id();
  if (std::any_of(maps_.begin(), maps_.end(), [id](const auto& m) { return m->id() == id; })) {
    throw Error("atlas: a map with id " + std::to_string(id) + " exists already");
  }
  const auto at = std::lower_bound(maps_.begin(), maps_.end(), id,
                                   [](const std::unique_ptr<Map>& m, std::uint64_t i) { return m->id() < i; });
  Map& added = **maps_.insert(at, std::move(map));
  next_map_id_ = std::max(next_map_id_, id + 1);
  return added;
}

Map& Atlas::active_map() const {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& m : maps_) {
    if (m->id() == active_) return *m;
  }
  throw Error("atlas: no active map");  // unreachable: the active map is never removed
}

std::uint64_t Atlas::active_map_id() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return active_;
}

void Atlas::set_active_map(std::uint64_t id) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (std::none_of(maps_.begin(), maps_.end(), [id](const auto& m) { return m->id() == id; })) {
    throw Error("atlas: no map with id " + std::to_string(id));
  }
  active_ = id;
}

std::vector<Map*> Atlas::maps() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<Map*> out;
  for (const auto& m : maps_) out.push_back(m.get());
  return out;
}

Map* Atlas::map(std::uint64_t id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& m : maps_) {
    if (m->id() == id) return m.get();
  }
  return nullptr;
}

std::size_t Atlas::num_maps() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return maps_.size();
}

std::uint64_t Atlas::maps_created() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return next_map_id_;
}

void Atlas::remove_map(std::uint64_t id) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = std::find_if(maps_.begin(), maps_.end(), [id](const auto& m) { return m->id() == id; });
  if (it == maps_.end()) throw Error("atlas: no map with id " + std::to_string(id));
  if (id == active_) throw Error("atlas: cannot remove the active map " + std::to_string(id));
  if (!(*it)->empty()) throw Error("atlas: map " + std::to_string(id) + " still holds keyframes or points");
  maps_.erase(it);
}

void Atlas::replace_maps(std::vector<std::unique_ptr<Map>> maps, std::uint64_t active, std::uint64_t next_map_id) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (maps.empty()) throw Error("atlas: no maps to load");
  if (std::any_of(maps_.begin(), maps_.end(), [](const auto& m) { return !m->empty(); })) {
    throw Error("atlas: maps can only be loaded into an empty atlas");
  }
  std::sort(maps.begin(), maps.end(), [](const auto& a, const auto& b) { return a->id() < b->id(); });
  if (std::none_of(maps.begin(), maps.end(), [active](const auto& m) { return m->id() == active; })) {
    throw Error("atlas: the active map " + std::to_string(active) + " is not among the loaded maps");
  }
  maps_ = std::move(maps);
  active_ = active;
  next_map_id_ = std::max(next_map_id, maps_.back()->id() + 1);
}

std::optional<std::uint64_t> Atlas::map_of_keyframe(std::uint64_t keyframe_id) const {
  for (Map* m : maps()) {
    std::lock_guard<std::mutex> lock(m->update_mutex());
    const auto& all = m->all_keyframes();
    const auto it = std::lower_bound(all.begin(), all.end(), keyframe_id,
                                     [](const KeyFramePtr& kf, std::uint64_t id) { return kf->id() < id; });
    if (it != all.end() && (*it)->id() == keyframe_id) return m->id();
  }
  return std::nullopt;
}

}  // namespace stillslam
