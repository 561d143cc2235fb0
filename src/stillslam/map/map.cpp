#include "stillslam/map/map.h"

#include <algorithm>

#include "stillslam/map/frame.h"

namespace stillslam {

Map::Map() : ids_(std::make_shared<MapIdCounters>()) {}

Map::Map(std::uint64_t id, std::shared_ptr<MapIdCounters> ids) : id_(id), ids_(std::move(ids)) {
  if (!ids_) ids_ = std::make_shared<MapIdCounters>();
}

KeyFramePtr Map::create_keyframe(const Frame& frame) {
  auto kf = std::make_shared<KeyFrame>(ids_->next_keyframe++, frame);
  kf->set_origin(all_keyframes_.empty());
  keyframes_.emplace(kf->id(), kf);
  all_keyframes_.push_back(kf);
  return kf;
}

MapPointPtr Map::create_map_point(const Eigen::Vector3d& position_world, KeyFrame* reference) {
  auto mp = std::make_shared<MapPoint>(ids_->next_point++, position_world, reference);
  points_.emplace(mp->id(), mp);
  return mp;
}

void Map::erase_keyframe(const KeyFramePtr& kf) {
  kf->set_bad();
  if (kf->is_bad()) keyframes_.erase(kf->id());
}

void Map::remove_bad_points() {
  for (auto it = points_.begin(); it != points_.end();) {
    it = it->second->is_bad() ? points_.erase(it) : std::next(it);
  }
}

void Map::add_keyframe(const KeyFramePtr& kf) {
  if (!kf->is_bad()) keyframes_.emplace(kf->id(), kf);
  const auto at = std::lower_bound(all_keyframes_.begin(), all_keyframes_.end(), kf,
                                   [](const KeyFramePtr& a, const KeyFramePtr& b) { return a->id() < b->id(); });
  all_keyframes_.insert(at, kf);
}

void Map::add_map_point(const MapPointPtr& mp) { points_.emplace(mp->id(), mp); }

void Map::absorb(Map& other) {
  if (&other == this) return;
  for (const KeyFramePtr& kf : other.all_keyframes_) add_keyframe(kf);
  for (const auto& [id, mp] : other.points_) {
    if (!mp->is_bad()) add_map_point(mp);
  }
  other.keyframes_.clear();
  other.all_keyframes_.clear();
  other.points_.clear();
}

std::vector<KeyFramePtr> Map::keyframes() const {
  std::vector<KeyFramePtr> out;
  out.reserve(keyframes_.size());
  for (const auto& [id, kf] : keyframes_) out.push_back(kf);
  return out;
}

std::vector<MapPointPtr> Map::map_points() const {
  std::vector<MapPointPtr> out;
  out.reserve(points_.size());
  for (const auto& [id, mp] : points_) {
    if (!mp->is_bad()) out.push_back(mp);
  }
  return out;
}

std::size_t Map::num_map_points() const {
  std::size_t n = 0;
  for (const auto& [id, mp] : points_) n += mp->is_bad() ? 0 : 1;
  return n;
}

KeyFramePtr Map::keyframe(std::uint64_t id) const {
  const auto it = keyframes_.find(id);
  return it == keyframes_.end() ? nullptr : it->second;
}

}  // namespace stillslam
